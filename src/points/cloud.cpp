#include "pss/points/cloud.hpp"

#include <algorithm>
#include <cmath>

namespace pss {

glm::dvec3 local_origin(const glm::dvec3& lo, const glm::dvec3& hi, const glm::dvec3& centre) {
  const glm::dvec3 size = hi - lo;
  const double extent = std::max({size.x, size.y, size.z});
  if (!(extent > 0)) return glm::dvec3(0.0);  // one position, or all equal: nothing to resolve
  const double step = std::exp2(std::ceil(std::log2(extent)));
  glm::dvec3 origin(0.0);
  for (int k = 0; k < 3; ++k)
    if (std::max(std::abs(lo[k]), std::abs(hi[k])) > 4 * extent) origin[k] = std::round(centre[k] / step) * step;
  return origin;
}

glm::dvec3 local_origin(const glm::dvec3& lo, const glm::dvec3& hi) { return local_origin(lo, hi, 0.5 * (lo + hi)); }

glm::dvec3 bulk_origin(const BulkSample& sample, const glm::dvec3& lo, const glm::dvec3& hi) {
  const BulkSample::Bulk bulk = BulkSample::bulk_of(sample.kept());
  return BulkSample::box_of_strays(bulk, lo, hi) ? local_origin(bulk.lo, bulk.hi, bulk.median) : local_origin(lo, hi);
}

namespace {

template <class Position>
glm::dvec3 origin_of(const std::vector<Position>& world) {
  glm::dvec3 lo(0.0), hi(0.0);
  if (!world.empty()) lo = hi = glm::dvec3(world.front());
  BulkSample sample;
  for (const Position& p : world) {
    lo = glm::min(lo, glm::dvec3(p));
    hi = glm::max(hi, glm::dvec3(p));
    sample.add(glm::dvec3(p));
  }
  return bulk_origin(sample, lo, hi);
}

}  // namespace

void set_world_positions(PointCloud& cloud, const std::vector<glm::dvec3>& world) {
  cloud.origin = origin_of(world);
  cloud.positions.resize(world.size());
  for (std::size_t i = 0; i < world.size(); ++i) cloud.positions[i] = vec3(world[i] - cloud.origin);
}

void set_world_positions(PointCloud& cloud, std::vector<vec3>&& world) {
  cloud.origin = origin_of(world);
  cloud.positions = std::move(world);
  if (cloud.origin != glm::dvec3(0.0))
    for (vec3& p : cloud.positions) p = vec3(glm::dvec3(p) - cloud.origin);
}

}  // namespace pss
