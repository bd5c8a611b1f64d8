#include "pss/points/cloud.hpp"

#include <algorithm>
#include <cmath>

namespace pss {

glm::dvec3 local_origin(const glm::dvec3& lo, const glm::dvec3& hi) {
  const glm::dvec3 size = hi - lo;
  const double extent = std::max({size.x, size.y, size.z});
  const double reach = std::max({std::abs(lo.x), std::abs(lo.y), std::abs(lo.z), std::abs(hi.x), std::abs(hi.y),
                                 std::abs(hi.z)});
  // One position, or all equal: nothing to resolve between them.
  if (!(extent > 0) || !(reach > 4 * extent)) return glm::dvec3(0.0);
  const double step = std::exp2(std::ceil(std::log2(extent)));
  return glm::round(0.5 * (lo + hi) / step) * step;
}

void set_world_positions(PointCloud& cloud, const std::vector<glm::dvec3>& world) {
  glm::dvec3 lo(0.0), hi(0.0);
  if (!world.empty()) lo = hi = world.front();
  for (const glm::dvec3& p : world) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  cloud.origin = local_origin(lo, hi);
  cloud.positions.resize(world.size());
  for (std::size_t i = 0; i < world.size(); ++i) cloud.positions[i] = vec3(world[i] - cloud.origin);
}

}  // namespace pss
