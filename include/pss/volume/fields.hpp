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
  float smoothing = 1;  // k of θ1, in value units
  // Fragment culling (§5.1): iso projects samples with |v − f| ≤ threshold (value units);
  // gradient those with θ2 > threshold (the paper's 0.5).
  float threshold = 0;
};

// The volume with its gradients and feature weights, as kernels see it.
struct FieldView {
  VolumeView volume;
  const vec3* gradients = nullptr;  // ∇f per voxel, in value per world unit
  const float* weights = nullptr;   // θ1 or θ2 per voxel, for the FeatureParams in use
  float inv_max_gradient2 = 0;      // 1 / max|∇f|²

  PSS_HOST_DEVICE vec3 gradient_at(vec3 p) const {
    return trilinear(gradients, volume.dims, TrilinearCell::at(volume.dims, volume.to_grid(p)));
  }
};

// θ1 as it recovers the iso-surface: exp(−|v − f|²/k²), largest AT the iso-value. The
// paper prints 1 − exp(−|v − f|²/k²), which is largest far from it; tests/volume_projection_test
// shows that form drives the fit away from the surface (docs/paper-notes.md, §4).
PSS_INLINE float theta_iso(float value, const FeatureParams& f) {
  const float d = (f.iso - value) / f.smoothing;
  return exp(-d * d);
}
// θ2 = (|∇f| / max|∇f|)².
PSS_INLINE float theta_gradient(vec3 gradient, float inv_max_gradient2) {
  return length2(gradient) * inv_max_gradient2;
}
// θ1 or θ2 of one voxel.
PSS_INLINE float feature_weight(const VolumeView& volume, const vec3* gradients, float inv_max_gradient2,
                                const FeatureParams& f, std::int64_t voxel) {
  return f.kind == FeatureKind::iso ? theta_iso(volume.values[voxel], f)
                                    : theta_gradient(gradients[voxel], inv_max_gradient2);
}

// The fragment test of §5.1 at a sample position.
PSS_INLINE bool passes_feature_test(const FieldView& v, const FeatureParams& f, vec3 p) {
  const TrilinearCell cell = TrilinearCell::at(v.volume.dims, v.volume.to_grid(p));
  if (f.kind == FeatureKind::iso) return abs(f.iso - trilinear(v.volume.values, v.volume.dims, cell)) <= f.threshold;
  return theta_gradient(trilinear(v.gradients, v.volume.dims, cell), v.inv_max_gradient2) > f.threshold;
}

// The host owner of the precomputed fields.
struct VolumeFields {
  Volume volume;
  std::vector<vec3> gradients;
  std::vector<float> weights;  // empty until set_feature()
  float max_gradient = 0;

  float inv_max_gradient2() const { return max_gradient > 0 ? 1.0f / (max_gradient * max_gradient) : 0.0f; }
  FieldView view() const { return {volume.view(), gradients.data(), weights.data(), inv_max_gradient2()}; }
};

// Precomputes every voxel's θ1 or θ2 for `feature` (once per image, not per projection).
void set_feature(VolumeFields& fields, const FeatureParams& feature);

// Gradients by central differences, each smoothed across the other two axes with the Sobel
// weights (1, 2, 1)/4; at the border the difference is one-sided. Parallel on the CPU.
VolumeFields compute_fields(Volume volume);

// The documented defaults, in voxels u (VolumeView::voxel_size) turned into value units by
// g = the iso-surface's mean |∇f|·u: θ1's k = g (1 voxel), and the culling threshold b·g/u
// (samples about a step b from the surface pass), both capped at half the way from v to
// the nearer end of the value range. 0 for smoothing or threshold means "default". The
// gradient mode's threshold defaults to the paper's 0.5.
FeatureParams iso_feature(const VolumeFields& fields, float iso, float step, float smoothing = 0, float threshold = 0);
FeatureParams gradient_feature(float threshold = 0);

// The mean |∇f| where the iso-surface crosses a grid edge (0 if it crosses none): turns
// distances in voxels into value units for the defaults of θ1's k and the culling threshold.
float iso_surface_gradient(const VolumeFields& fields, float iso);

}  // namespace pss
