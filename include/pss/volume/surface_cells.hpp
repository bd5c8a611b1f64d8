// Whether the volume has a surface near a point (issue 7, docs/paper-notes.md §5.1). The
// paper's fragment test |v − f| ≤ threshold is a culling heuristic, and real data defeat
// it: a noisy background a little below v passes it and the fit then draws sheets in empty
// space. The iso-surface exists exactly where the data's trilinear interpolant crosses v,
// which happens in a cell of the voxel lattice if and only if its eight corners straddle v
// (the interpolant is multilinear, so it stays within its corners' range and takes every
// value between them). That is the marching-cubes criterion, and the one we use: samples
// are projected only within reach of such a cell, and a hit is accepted only next to one.
// The predictor and corrector still decide *where* the surface is. A gradient surface has
// its own criterion: cells with a corner of θ2 above the threshold.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/vector_relational.hpp>

#include "pss/volume/fields.hpp"

namespace pss {

enum SurfaceCellFlag : std::uint8_t {
  kCellCrossed = 1,  // the surface passes through the cell
  kCellBeside = 2,   // the cell is a crossed one or one of its 26 neighbours: hits may lie here
  kCellInReach = 4,  // within the marching reach of a crossed cell: samples here are projected
};

// One flag byte per cell; cell (i, j, k) spans voxels i..i+1, j..j+1, k..k+1.
struct CellView {
  const std::uint8_t* flags = nullptr;
  ivec3 count{0};

  // The cell holding continuous grid coordinate g, clamped into the lattice.
  PSS_HOST_DEVICE ivec3 cell_of(vec3 g) const {
    return glm::clamp(ivec3(int(floor(g.x)), int(floor(g.y)), int(floor(g.z))), ivec3(0), count - 1);
  }
  PSS_HOST_DEVICE std::uint8_t at(ivec3 c) const {
    return flags[(std::int64_t(c.z) * count.y + c.y) * count.x + c.x];
  }
  PSS_HOST_DEVICE bool has(vec3 g, SurfaceCellFlag flag) const { return (at(cell_of(g)) & flag) != 0; }
};

struct SurfaceCells {
  std::vector<std::uint8_t> flags;
  ivec3 count{0};
  std::int64_t crossed_count = 0;
  Aabb crossed_bounds;  // world box of the crossed cells; empty when there are none

  CellView view() const { return {flags.data(), count}; }
};

// The fragment test (§5.1) at the world position p: p is within reach of a crossed cell,
// and for an iso-surface the data say the surface may be within `reach` of p: the
// first-order distance |v − f(p)|/|∇f(p)| is at most twice the reach (twice: on a step
// sharper than a voxel the Sobel gradient halves the slope). A gradient surface's crossed
// cells are those with a corner of θ2 above the threshold, and nearness to one is its whole
// test: the paper's own, θ2 > threshold at p, misses a ridge of θ2 thinner than the step
// between a ray's samples, and the tooth's render showed terraces where rays crossed it
// between two samples (docs/paper-notes.md, §5.1 marching).
PSS_INLINE bool passes_feature_test(const FieldView& v, const CellView& cells, const FeatureParams& f, vec3 p,
                                    float reach) {
  const vec3 g = v.volume.to_grid(p);
  if (!cells.has(g, kCellInReach)) return false;
  if (f.kind == FeatureKind::gradient) return true;  // in reach of a cell above the threshold
  const TrilinearCell cell = TrilinearCell::at(v.volume.dims, g);
  const vec3 gradient = trilinear(v.gradients, v.volume.dims, cell);
  const float difference = abs(f.iso - trilinear(v.volume.values, v.volume.dims, cell));
  return difference <= 2.0f * reach * glm::length(gradient);
}

// Whether a projection that settled at p, with the fitted surface's normal n, is a hit:
// the data's surface is there. For an iso-surface the interpolant crosses v on the segment
// p ± reach·n (sampled every quarter voxel), reach being how far the PSS, a surface
// smoothed at the scale h, may stand off the interpolant's (which keeps the noise); a fit
// that settled beside a small blob or off the rim of a cap has no crossing along its normal.
// The reach is a length in the lattice's metric, as h is (VolumeView::metric): across thick
// slices it spans as many slices as across thin ones. A gradient surface needs p next to a
// cell of high θ2.
PSS_INLINE bool is_data_surface(const FieldView& v, const CellView& cells, const FeatureParams& f, vec3 p, vec3 n,
                                float reach) {
  if (!cells.has(v.volume.to_grid(p), kCellBeside)) return false;
  if (f.kind == FeatureKind::gradient) return true;
  const int steps = max(1, int(ceil(4.0f * reach / v.volume.voxel_size())));
  const vec3 metric = v.volume.metric();
  const float along = metric == vec3(1.0f) ? reach : reach / glm::length(n * metric);  // in space, along n
  bool below = false, above = false;
  const Aabb box = v.volume.bounds();
  for (int i = -steps; i <= steps; ++i) {
    // Only inside the box: beyond it the data are not known (sampling would clamp to the
    // face's values and make a crossing of the face itself).
    const vec3 q = p + (along * float(i) / float(steps)) * n;
    if (glm::any(glm::lessThan(q, box.lo)) || glm::any(glm::greaterThan(q, box.hi))) continue;
    const float value = sample(v.volume, q);
    below = below || value <= f.iso;
    above = above || value >= f.iso;
  }
  return below && above;
}

// The cells of `fields` for `feature`; `reach` (world units) is how far from a crossed cell
// a sample may lie and still be projected (prepare_volume: b/2, half the marching step).
SurfaceCells find_surface_cells(const VolumeFields& fields, const FeatureParams& feature, float reach);

}  // namespace pss
