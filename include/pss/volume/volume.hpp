// A scalar volume on a uniform grid (paper §4): values as float, dims, spacing and origin.
// Voxel (i, j, k) sits at origin + (i·sx, j·sy, k·sz), x fastest in memory. The host owns
// the arrays (Volume); kernels read them through VolumeView, pointers + sizes by value.
#pragma once

#include <cstdint>
#include <vector>

#include "pss/core/types.hpp"

namespace pss {

struct VolumeView {
  const float* values = nullptr;
  ivec3 dims{0};
  vec3 spacing{1.0f};
  vec3 origin{0.0f};

  PSS_HOST_DEVICE std::int64_t index(int i, int j, int k) const {
    return (std::int64_t(k) * dims.y + j) * dims.x + i;
  }
  PSS_HOST_DEVICE float at(int i, int j, int k) const { return values[index(i, j, k)]; }
  PSS_HOST_DEVICE vec3 position(int i, int j, int k) const {
    return origin + vec3(float(i), float(j), float(k)) * spacing;
  }
  // World position → continuous voxel coordinates.
  PSS_HOST_DEVICE vec3 to_grid(vec3 p) const { return (p - origin) / spacing; }
  // The box spanned by the voxel centres: where trilinear interpolation is defined.
  PSS_HOST_DEVICE Aabb bounds() const {
    return {origin, origin + vec3(float(dims.x - 1), float(dims.y - 1), float(dims.z - 1)) * spacing};
  }
  // The voxel unit u of the method's defaults: the edge of a cube of one voxel's volume,
  // so that a ball of a few u holds several layers of voxels along every axis.
  PSS_HOST_DEVICE float voxel_size() const { return pow(spacing.x * spacing.y * spacing.z, 1.0f / 3.0f); }
  // The neighbourhoods' metric: an offset d weighs as |d ⊙ metric()|, its length in lattice
  // steps times u, so that a ball of a few u holds a few layers along every axis however
  // unequal the spacing (a CT's slices 6× the pixels: a round ball of 3u held one slice).
  // Exactly 1 on a cubic grid.
  PSS_HOST_DEVICE vec3 metric() const {
    if (spacing.x == spacing.y && spacing.y == spacing.z) return vec3(1.0f);
    return voxel_size() / spacing;
  }
};

// The cell holding continuous grid coordinate g (clamped into the grid) and the fractions
// within it: the shared first step of every trilinear lookup.
struct TrilinearCell {
  int i, j, k;
  vec3 f;

  PSS_HOST_DEVICE static TrilinearCell at(ivec3 dims, vec3 g) {
    TrilinearCell c;
    const vec3 hi = vec3(float(dims.x - 1), float(dims.y - 1), float(dims.z - 1));
    g = glm::clamp(g, vec3(0.0f), hi);
    c.i = min(int(g.x), max(dims.x - 2, 0));
    c.j = min(int(g.y), max(dims.y - 2, 0));
    c.k = min(int(g.z), max(dims.z - 2, 0));
    c.f = g - vec3(float(c.i), float(c.j), float(c.k));
    return c;
  }
};

// Trilinear interpolation of any per-voxel array laid out like the volume.
template <class T>
PSS_HOST_DEVICE T trilinear(const T* data, ivec3 dims, const TrilinearCell& c) {
  const int di = dims.x > 1 ? 1 : 0;
  const std::int64_t dj = dims.y > 1 ? dims.x : 0;
  const std::int64_t dk = dims.z > 1 ? std::int64_t(dims.x) * dims.y : 0;
  const std::int64_t base = (std::int64_t(c.k) * dims.y + c.j) * dims.x + c.i;
  const T c00 = data[base] * (1 - c.f.x) + data[base + di] * c.f.x;
  const T c10 = data[base + dj] * (1 - c.f.x) + data[base + dj + di] * c.f.x;
  const T c01 = data[base + dk] * (1 - c.f.x) + data[base + dk + di] * c.f.x;
  const T c11 = data[base + dk + dj] * (1 - c.f.x) + data[base + dk + dj + di] * c.f.x;
  const T c0 = c00 * (1 - c.f.y) + c10 * c.f.y;
  const T c1 = c01 * (1 - c.f.y) + c11 * c.f.y;
  return c0 * (1 - c.f.z) + c1 * c.f.z;
}

// The value at a world position, clamped to the grid's box.
PSS_INLINE float sample(const VolumeView& v, vec3 p) {
  return trilinear(v.values, v.dims, TrilinearCell::at(v.dims, v.to_grid(p)));
}

// The host owner.
struct Volume {
  ivec3 dims{0};
  vec3 spacing{1.0f};
  vec3 origin{0.0f};
  std::vector<float> values;

  std::int64_t voxel_count() const { return std::int64_t(dims.x) * dims.y * dims.z; }
  VolumeView view() const { return {values.data(), dims, spacing, origin}; }
};

}  // namespace pss
