#include "pss/core/bulk_sample.hpp"

#include <algorithm>

#include <glm/common.hpp>

namespace pss {

BulkSample::Bulk BulkSample::bulk_of(std::vector<glm::dvec3> positions) {
  Bulk b;
  const std::size_t n = positions.size();
  if (n == 0) return b;
  std::vector<double> axis(n);
  for (int k = 0; k < 3; ++k) {
    for (std::size_t i = 0; i < n; ++i) axis[i] = positions[i][k];
    std::sort(axis.begin(), axis.end());
    b.lo[k] = axis[n / 50];
    b.hi[k] = axis[n - 1 - n / 50];
    b.median[k] = axis[n / 2];
  }
  return b;
}

bool BulkSample::box_of_strays(const Bulk& bulk, const glm::dvec3& lo, const glm::dvec3& hi) {
  const glm::dvec3 size = bulk.hi - bulk.lo, off = glm::abs(0.5 * (lo + hi) - bulk.median);
  const double extent = std::max({size.x, size.y, size.z});
  return extent > 0 && std::max({off.x, off.y, off.z}) > extent;
}

}  // namespace pss
