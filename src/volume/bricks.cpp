#include "pss/volume/bricks.hpp"

#include <algorithm>

#include "pss/backend/cpu/parallel_for.hpp"

namespace pss {

BrickGrid build_bricks(const VolumeFields& fields, const FeatureParams& feature) {
  const VolumeView v = fields.volume.view();
  const FieldView fv = fields.view();
  BrickGrid grid;
  const ivec3 cells = glm::max(v.dims - 1, ivec3(1));
  grid.count = (cells + kBrickCells - 1) / kBrickCells;
  grid.occupied.assign(std::size_t(grid.count.x) * grid.count.y * grid.count.z, 0);
  cpu::parallel_for(std::int64_t(grid.occupied.size()), [&](std::int64_t b) {
    const int bx = int(b % grid.count.x), by = int(b / grid.count.x % grid.count.y);
    const int bz = int(b / (std::int64_t(grid.count.x) * grid.count.y));
    const ivec3 lo = ivec3(bx, by, bz) * kBrickCells;
    const ivec3 hi = glm::min(lo + kBrickCells, v.dims - 1);
    // Iso-surfaces need the value range, gradient surfaces the largest θ2: only that is read.
    const bool iso = feature.kind == FeatureKind::iso;
    float lo_value = kInfinity, hi_value = -kInfinity, hi_theta = 0;
    for (int k = lo.z; k <= hi.z; ++k)
      for (int j = lo.y; j <= hi.y; ++j)
        for (int i = lo.x; i <= hi.x; ++i) {
          const std::int64_t index = v.index(i, j, k);
          if (iso) {
            lo_value = std::min(lo_value, v.values[index]);
            hi_value = std::max(hi_value, v.values[index]);
          } else {
            hi_theta = std::max(hi_theta, theta_gradient(fields.gradients[std::size_t(index)], fv.inv_max_gradient2));
          }
        }
    const bool may_pass = iso ? lo_value <= feature.iso + feature.threshold && hi_value >= feature.iso - feature.threshold
                              : hi_theta > feature.threshold;
    grid.occupied[std::size_t(b)] = may_pass ? 1 : 0;
  });
  grid.occupied_count = std::count(grid.occupied.begin(), grid.occupied.end(), std::uint8_t(1));
  return grid;
}

}  // namespace pss
