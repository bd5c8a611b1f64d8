#include "pss/volume/fields.hpp"

#include <algorithm>
#include <cmath>

#include "pss/backend/cpu/parallel_for.hpp"

namespace pss {

namespace {

// One separable pass along `axis`: the Sobel smoothing (1, 2, 1)/4, renormalised where the
// border cuts it, or the central difference (one-sided at the border) divided by the
// distance it spans. Each task combines three whole x-rows, so memory is read in order
// whatever the axis.
enum class Pass { smooth, difference };

void line_pass(const float* in, float* out, ivec3 dims, int axis, Pass pass, float spacing) {
  const std::int64_t nx = dims.x;
  cpu::parallel_for(std::int64_t(dims.y) * dims.z, [&](std::int64_t row) {
    const int j = int(row % dims.y), k = int(row / dims.y);
    const std::int64_t base = row * nx;
    float* dst = out + base;
    if (axis == 0) {
      const float* src = in + base;
      for (int i = 0; i < dims.x; ++i) {
        const int lo = i > 0 ? i - 1 : i, hi = i + 1 < dims.x ? i + 1 : i;
        if (pass == Pass::smooth)
          dst[i] = ((lo < i ? src[lo] : 0.0f) + 2 * src[i] + (hi > i ? src[hi] : 0.0f)) /
                   ((lo < i ? 1.0f : 0.0f) + 2.0f + (hi > i ? 1.0f : 0.0f));
        else
          dst[i] = hi > lo ? (src[hi] - src[lo]) / (float(hi - lo) * spacing) : 0.0f;
      }
      return;
    }
    const int c = axis == 1 ? j : k, n = dims[axis];
    const std::int64_t stride = axis == 1 ? nx : nx * dims.y;
    const int lo = c > 0 ? c - 1 : c, hi = c + 1 < n ? c + 1 : c;
    const float* a = in + base + (lo - c) * stride;
    const float* m = in + base;
    const float* b = in + base + (hi - c) * stride;
    if (pass == Pass::smooth) {
      const float wa = lo < c ? 1.0f : 0.0f, wb = hi > c ? 1.0f : 0.0f, inv = 1.0f / (wa + 2.0f + wb);
      for (std::int64_t i = 0; i < nx; ++i) dst[i] = (wa * a[i] + 2 * m[i] + wb * b[i]) * inv;
    } else {
      const float inv = hi > lo ? 1.0f / (float(hi - lo) * spacing) : 0.0f;
      for (std::int64_t i = 0; i < nx; ++i) dst[i] = (b[i] - a[i]) * inv;
    }
  });
}

}  // namespace

VolumeFields compute_fields(Volume volume) {
  VolumeFields out;
  out.volume = std::move(volume);
  const VolumeView v = out.volume.view();
  const std::size_t n = std::size_t(out.volume.voxel_count());
  std::vector<float> a(n), b(n), d(n);
  out.gradients.assign(n, vec3(0.0f));
  // ∂f/∂x = Dx Sy Sz f, and so on: the 3-D Sobel operator is separable.
  const auto component = [&](int axis) {
    const int a1 = (axis + 1) % 3, a2 = (axis + 2) % 3;
    line_pass(v.values, a.data(), v.dims, a1, Pass::smooth, 1.0f);
    line_pass(a.data(), b.data(), v.dims, a2, Pass::smooth, 1.0f);
    line_pass(b.data(), d.data(), v.dims, axis, Pass::difference, v.spacing[axis]);
    cpu::parallel_for(std::int64_t(n), [&](std::int64_t i) { out.gradients[std::size_t(i)][axis] = d[std::size_t(i)]; });
  };
  for (int axis = 0; axis < 3; ++axis) component(axis);
  float max2 = 0;  // per unit of the lattice's metric, as θ2 (theta_gradient)
  const vec3 metric = v.metric();
  for (const vec3& x : out.gradients) max2 = std::max(max2, length2(x / metric));
  out.max_gradient = sqrt(max2);
  return out;
}

void set_feature(VolumeFields& fields, const FeatureParams& feature) {
  const VolumeView v = fields.volume.view();
  const float inv_max2 = fields.inv_max_gradient2();
  const vec3 metric = v.metric();
  fields.features.resize(fields.gradients.size());
  FeatureVoxel* out = fields.features.data();
  const vec3* g = fields.gradients.data();
  cpu::parallel_for(v.dims.x * std::int64_t(v.dims.y) * v.dims.z, [&](std::int64_t i) {
    const float length = glm::length(g[i]);
    out[i] = {feature_weight(v, metric, g, inv_max2, feature, i), length > 0 ? g[i] / length : vec3(0.0f)};
  });
}

FeatureParams iso_feature(float iso, float smoothing) {
  FeatureParams f;
  f.kind = FeatureKind::iso;
  f.iso = iso;
  f.smoothing = smoothing;
  return f;
}

FeatureParams gradient_feature(float threshold) {
  FeatureParams f;
  f.kind = FeatureKind::gradient;
  f.threshold = threshold;
  return f;
}

}  // namespace pss
