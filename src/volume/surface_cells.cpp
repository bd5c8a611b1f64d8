#include "pss/volume/surface_cells.hpp"

#include <algorithm>
#include <cmath>

#include "pss/backend/cpu/parallel_for.hpp"

namespace pss {

namespace {

// Sets `bit` on every cell within `radius` cells (per axis, a box) of a cell with `source`:
// one pass per axis, each marking the cells whose nearest source along the line (found by a
// forward and a backward sweep) is within the radius.
void dilate(std::vector<std::uint8_t>& flags, ivec3 count, std::uint8_t source, std::uint8_t bit, ivec3 radius) {
  std::vector<std::uint8_t> mask(flags.size());
  for (std::size_t i = 0; i < flags.size(); ++i) mask[i] = (flags[i] & source) ? 1 : 0;
  for (int axis = 0; axis < 3; ++axis) {
    const int n = count[axis], r = radius[axis];
    const std::int64_t stride = axis == 0 ? 1 : axis == 1 ? count.x : std::int64_t(count.x) * count.y;
    const int a1 = (axis + 1) % 3, a2 = (axis + 2) % 3;
    std::vector<std::uint8_t> out(mask.size());
    cpu::parallel_for(std::int64_t(count[a1]) * count[a2], [&](std::int64_t line) {
      ivec3 c(0);
      c[a1] = int(line % count[a1]);
      c[a2] = int(line / count[a1]);
      const std::int64_t base = (std::int64_t(c.z) * count.y + c.y) * count.x + c.x;
      int last = -r - 1;  // the nearest source at or before i
      for (int i = 0; i < n; ++i) {
        if (mask[std::size_t(base + i * stride)]) last = i;
        out[std::size_t(base + i * stride)] = i - last <= r;
      }
      int next = n + r + 1;  // the nearest source at or after i
      for (int i = n - 1; i >= 0; --i) {
        if (mask[std::size_t(base + i * stride)]) next = i;
        if (next - i <= r) out[std::size_t(base + i * stride)] = 1;
      }
    });
    mask.swap(out);
  }
  for (std::size_t i = 0; i < flags.size(); ++i)
    if (mask[i]) flags[i] |= bit;
}

}  // namespace

SurfaceCells find_surface_cells(const VolumeFields& fields, const FeatureParams& feature, float reach) {
  const VolumeView v = fields.volume.view();
  SurfaceCells out;
  out.count = glm::max(v.dims - 1, ivec3(1));
  const ivec3 count = out.count;
  out.flags.assign(std::size_t(count.x) * count.y * count.z, 0);
  // A corner index clamped into the grid, so that a volume one voxel thick still has cells.
  const auto corner = [&](int i, int j, int k) {
    return v.index(std::min(i, v.dims.x - 1), std::min(j, v.dims.y - 1), std::min(k, v.dims.z - 1));
  };
  const bool iso = feature.kind == FeatureKind::iso;
  cpu::parallel_for(std::int64_t(count.y) * count.z, [&](std::int64_t row) {
    const int j = int(row % count.y), k = int(row / count.y);
    for (int i = 0; i < count.x; ++i) {
      float lo = kInfinity, hi = -kInfinity;
      for (int c = 0; c < 8; ++c) {
        const std::int64_t index = corner(i + (c & 1), j + ((c >> 1) & 1), k + (c >> 2));
        const float x = iso ? v.values[index] : fields.weights[std::size_t(index)];
        lo = std::min(lo, x);
        hi = std::max(hi, x);
      }
      // Iso: the interpolant takes the value v somewhere in the cell iff lo ≤ v ≤ hi; a cell
      // that is flat at exactly v is not a surface. Gradient: θ2 exceeds the threshold there.
      const bool crossed = iso ? lo <= feature.iso && feature.iso <= hi && lo < hi : hi > feature.threshold;
      if (crossed) out.flags[std::size_t((std::int64_t(k) * count.y + j) * count.x + i)] = kCellCrossed;
    }
  });
  dilate(out.flags, count, kCellCrossed, kCellBeside, ivec3(1));
  const vec3 cells_in_reach = glm::ceil(vec3(reach) / v.spacing);
  dilate(out.flags, count, kCellCrossed, kCellInReach, ivec3(cells_in_reach));
  for (int k = 0; k < count.z; ++k)
    for (int j = 0; j < count.y; ++j)
      for (int i = 0; i < count.x; ++i)
        if (out.flags[std::size_t((std::int64_t(k) * count.y + j) * count.x + i)] & kCellCrossed) {
          ++out.crossed_count;
          out.crossed_bounds.grow(v.position(i, j, k));
          out.crossed_bounds.grow(v.position(std::min(i + 1, v.dims.x - 1), std::min(j + 1, v.dims.y - 1),
                                             std::min(k + 1, v.dims.z - 1)));
        }
  return out;
}

}  // namespace pss
