#include "pss/volume/surface_cells.hpp"

#include <algorithm>
#include <cmath>

#include "pss/backend/cpu/parallel_for.hpp"

namespace pss {

namespace {

// Sets `bit` on every cell within `radius` cells (per axis, a box) of a cell with `source`,
// one axis at a time. Along x a row is swept forward and backward for the nearest source;
// along y and z a row becomes the OR of the rows within the radius, whole rows at a time
// so that memory is read in order.
void dilate(std::vector<std::uint8_t>& flags, ivec3 count, std::uint8_t source, std::uint8_t bit, ivec3 radius) {
  std::vector<std::uint8_t> mask(flags.size()), out(flags.size());
  for (std::size_t i = 0; i < flags.size(); ++i) mask[i] = (flags[i] & source) ? 1 : 0;
  const std::int64_t rows = std::int64_t(count.y) * count.z, nx = count.x;
  cpu::parallel_for(rows, [&](std::int64_t row) {
    const std::uint8_t* in = mask.data() + row * nx;
    std::uint8_t* dst = out.data() + row * nx;
    const int r = radius.x;
    int last = -r - 1;  // the nearest source at or before i
    for (int i = 0; i < count.x; ++i) {
      if (in[i]) last = i;
      dst[i] = i - last <= r;
    }
    int next = count.x + r + 1;  // the nearest source at or after i
    for (int i = count.x - 1; i >= 0; --i) {
      if (in[i]) next = i;
      if (next - i <= r) dst[i] = 1;
    }
  });
  for (int axis = 1; axis < 3; ++axis) {
    mask.swap(out);
    const int n = count[axis], r = radius[axis];
    const std::int64_t stride = axis == 1 ? nx : nx * count.y;
    cpu::parallel_for(rows, [&](std::int64_t row) {
      const int c = int(axis == 1 ? row % count.y : row / count.y);
      std::uint8_t* dst = out.data() + row * nx;
      std::fill(dst, dst + nx, std::uint8_t(0));
      for (int d = std::max(-r, -c); d <= std::min(r, n - 1 - c); ++d) {
        const std::uint8_t* in = mask.data() + row * nx + d * stride;
        for (std::int64_t i = 0; i < nx; ++i) dst[i] |= in[i];
      }
    });
  }
  for (std::size_t i = 0; i < flags.size(); ++i)
    if (out[i]) flags[i] |= bit;
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
  // Per row: how many cells are crossed and the first and last crossed i, combined below.
  struct RowSpan {
    std::int64_t crossed = 0;
    int lo = 0, hi = -1;
  };
  std::vector<RowSpan> rows(std::size_t(count.y) * count.z);
  cpu::parallel_for(std::int64_t(rows.size()), [&](std::int64_t row) {
    const int j = int(row % count.y), k = int(row / count.y);
    RowSpan& span = rows[std::size_t(row)];
    for (int i = 0; i < count.x; ++i) {
      float lo = kInfinity, hi = -kInfinity;
      for (int c = 0; c < 8; ++c) {
        const std::int64_t index = corner(i + (c & 1), j + ((c >> 1) & 1), k + (c >> 2));
        const float x = iso ? v.values[index] : fields.features[std::size_t(index)].weight;
        lo = std::min(lo, x);
        hi = std::max(hi, x);
      }
      // Iso: the interpolant takes the value v somewhere in the cell iff lo ≤ v ≤ hi; a cell
      // that is flat at exactly v is not a surface. Gradient: θ2 exceeds the threshold there.
      const bool crossed = iso ? lo <= feature.iso && feature.iso <= hi && lo < hi : hi > feature.threshold;
      if (!crossed) continue;
      out.flags[std::size_t(row * count.x + i)] = kCellCrossed;
      if (span.crossed++ == 0) span.lo = i;
      span.hi = i;
    }
  });
  for (std::size_t row = 0; row < rows.size(); ++row) {
    if (!rows[row].crossed) continue;
    const int j = int(row % std::size_t(count.y)), k = int(row / std::size_t(count.y));
    out.crossed_count += rows[row].crossed;
    out.crossed_bounds.grow(v.position(rows[row].lo, j, k));
    out.crossed_bounds.grow(v.position(std::min(rows[row].hi + 1, v.dims.x - 1), std::min(j + 1, v.dims.y - 1),
                                       std::min(k + 1, v.dims.z - 1)));
  }
  dilate(out.flags, count, kCellCrossed, kCellBeside, ivec3(1));
  const vec3 cells_in_reach = glm::ceil(vec3(reach) / v.spacing);
  dilate(out.flags, count, kCellCrossed, kCellInReach, ivec3(cells_in_reach));
  return out;
}

}  // namespace pss
