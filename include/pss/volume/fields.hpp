// What the method precomputes per voxel (paper §5.1): the gradient by central differences
// filtered with the Sobel operator, its largest magnitude, and the feature weights θ1 / θ2
// of §4 that pick the surface out of the volume.
#pragma once

#include "pss/volume/volume.hpp"

namespace pss {

enum class FeatureKind : unsigned char {
  iso,       // θ1: voxels whose value is near the iso-value v
  gradient,  // θ2: voxels of high gradient magnitude
};

struct FeatureParams {
  FeatureKind kind = FeatureKind::iso;
  float iso = 0;        // v
  float smoothing = 1;  // k of θ1: the width, in world units, of its Gaussian in distance
  // Gradient surfaces: samples with θ2 > threshold are projected (the paper's 0.5). Iso-surfaces
  // need none: whether a sample is near the surface is decided by the data (surface_cells.hpp).
  float threshold = 0;
};

// What a neighbourhood gather reads of one voxel, in one 16-byte load: its θ1 or θ2 and the
// direction of its gradient (0 where ∇f = 0), which the facing test of N(x) needs
// (projection.hpp) and which would otherwise cost a square root and a division per voxel.
struct alignas(16) FeatureVoxel {
  float weight;
  vec3 direction;
};
static_assert(sizeof(FeatureVoxel) == 16);

// The volume with its gradients and feature weights, as kernels see it.
struct FieldView {
  VolumeView volume;
  const vec3* gradients = nullptr;         // ∇f per voxel, in value per world unit
  // θ1 or θ2 and ∇f/|∇f| per voxel, for the FeatureParams in use: one record per voxel (the
  // CPU's gather reads whole rows of eight, volume/voxel_gather_avx2.hpp).
  const FeatureVoxel* features = nullptr;
  float inv_max_gradient2 = 0;             // 1 / max|∇f|², ∇f per unit of the metric (theta_gradient)

  PSS_HOST_DEVICE vec3 gradient_at(vec3 p) const {
    return trilinear(gradients, volume.dims, TrilinearCell::at(volume.dims, volume.to_grid(p)));
  }
};

// θ1 as it recovers the iso-surface: exp(−|v − f|²/(k·|∇f|)²), largest AT the iso-value.
// The paper prints 1 − exp(−|v − f|²/k²), which is largest far from it; tests/
// volume_projection_test shows that form drives the fit away from the surface. And its k
// is one width in value units for the whole volume, while |v − f| saturates away from a
// sharp edge (air is air however far from the skin): with k from the surface's mean
// gradient, every voxel of a CT's background then weighs about as much as those at the
// edge, and the fit of Eq. 3 returns the ball's centre, not the surface (wood-grain
// terraces on the sample lattice, sheets in empty space). Dividing by the voxel's own
// |∇f| makes |v − f|/|∇f| the first-order distance from the voxel to the iso-surface, so
// k is a width in world units and far voxels, where f is flat, weigh nothing
// (docs/paper-notes.md, §4). On a grid of unequal spacing the distance is measured in the
// lattice's metric, as the neighbourhoods are (VolumeView::metric): `gradient` per unit of it.
PSS_INLINE float theta_iso(float value, vec3 gradient, const FeatureParams& f) {
  const float difference = f.iso - value;
  const float width2 = f.smoothing * f.smoothing * length2(gradient);
  if (!(width2 > 0)) return difference == 0 ? 1.0f : 0.0f;
  return exp(-difference * difference / width2);
}
// θ2 = (|∇f| / max|∇f|)². On a grid of unequal spacing ∇f is taken per unit of the
// lattice's metric (VolumeView::metric), the max too: a step in the data is a jump between
// neighbouring voxels, which across slices 6× the pixels is 1/6 as steep in space, and θ2
// in space kept only the surfaces facing across the pixels. Per lattice step every voxel's
// θ2 is that of the same values on a cubic grid.
PSS_INLINE float theta_gradient(vec3 gradient, float inv_max_gradient2) {
  return length2(gradient) * inv_max_gradient2;
}
// θ1 or θ2 of one voxel; `metric` is volume.metric(), which the caller computes once.
PSS_INLINE float feature_weight(const VolumeView& volume, vec3 metric, const vec3* gradients, float inv_max_gradient2,
                                const FeatureParams& f, std::int64_t voxel) {
  return f.kind == FeatureKind::iso ? theta_iso(volume.values[voxel], gradients[voxel] / metric, f)
                                    : theta_gradient(gradients[voxel] / metric, inv_max_gradient2);
}

// The host owner of the precomputed fields.
struct VolumeFields {
  Volume volume;
  std::vector<vec3> gradients;
  std::vector<FeatureVoxel> features;  // empty until set_feature()
  float max_gradient = 0;  // max|∇f| per unit of the lattice's metric (theta_gradient)

  float inv_max_gradient2() const { return max_gradient > 0 ? 1.0f / (max_gradient * max_gradient) : 0.0f; }
  FieldView view() const { return {volume.view(), gradients.data(), features.data(), inv_max_gradient2()}; }
};

// Precomputes every voxel's θ1 or θ2 for `feature` (once per image, not per projection).
void set_feature(VolumeFields& fields, const FeatureParams& feature);

// Gradients by central differences, each smoothed across the other two axes with the Sobel
// weights (1, 2, 1)/4; at the border the difference is one-sided. Parallel on the CPU.
VolumeFields compute_fields(Volume volume);

// θ1's default k, in voxels. On a step sharper than a voxel only the two layers of voxels
// beside the edge carry weight, and their first-order distances |v − f|/|∇f| range from
// about ±0.3 to ±1.7 voxels as the edge moves within the cell: k must let both layers weigh
// (k ≳ 1.2), while a thinner shell follows curvature more closely (k small).
// tests/volume_sharp_edge_test and volume_render_test measure both ends (docs/paper-notes.md).
inline constexpr float kIsoSmoothingVoxels = 1.25f;

// The feature parameters. θ1's k is in world units (the CLI's --smoothing is in voxels);
// the gradient mode's threshold defaults to the paper's 0.5.
FeatureParams iso_feature(float iso, float smoothing);
FeatureParams gradient_feature(float threshold = 0.5f);

}  // namespace pss
