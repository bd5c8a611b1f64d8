// APSS, algebraic point set surfaces (Guennebaud & Gross, SIGGRAPH 2007), the projection of
// `--surface apss`: at x, the algebraic sphere f(y) = u0 + u·y + u4‖y‖² that best fits the
// samples and their normals with the weights from x, with ∇f matched to the normals (the
// "normal constraint" fit, closed form); x projects onto its zero set. A sphere holds a
// curved patch where a plane cannot: sparse or thin curved parts keep their shape, and a
// sampled sphere is reproduced exactly.
#pragma once

#include "pss/core/frame.hpp"
#include "pss/fit/polynomial.hpp"
#include "pss/fit/weights.hpp"
#include "pss/points/projection.hpp"

namespace pss {

// f(y) = u0 + u·y + u4‖y‖², y = (p − origin)/scale in the fit's coordinates
// (fit_algebraic_sphere). u4 = 0 is a plane.
struct AlgebraicSphere {
  float u0 = 0;
  vec3 u{0.0f};
  float u4 = 0;
  bool valid = false;

  PSS_HOST_DEVICE vec3 gradient_at(vec3 y) const { return u + 2 * u4 * y; }
};

// The fit of Guennebaud & Gross (2007, Eq. 6 and 7) with the weights θ3(‖p_i − origin‖):
//   u4 = ½·(Σw p·n − Σw p·Σw n/Σw) / (Σw p·p − Σw p·Σw p/Σw),
//   u  = (Σw n − 2u4 Σw p)/Σw,   u0 = −(u·Σw p + u4 Σw p·p)/Σw,
// in coordinates about `origin` in units of `scale`, so that single precision holds its
// digits. Invalid without weight; a plane where the samples have no spread.
template <class Samples>
PSS_HOST_DEVICE AlgebraicSphere fit_algebraic_sphere(const Samples& samples, vec3 origin,
                                                     float scale) {
  AlgebraicSphere s;
  const float inv_scale = 1 / scale;
  float sw = 0, spn = 0, spp = 0;
  vec3 sp(0.0f), sn(0.0f);
  samples.for_each_sample([&](vec3 p, int i) {
    const vec3 d = p - origin;
    const float w = samples.grid->mass_of(i) * gaussian_weight(length2(d), samples.grid->inv_h2[i]);
    const vec3 y = d * inv_scale;
    const vec3 n = samples.grid->normals[i];
    sw += w;
    sp += w * y;
    sn += w * n;
    spn += w * glm::dot(y, n);
    spp += w * length2(y);
  });
  if (!(sw > 0)) return s;
  const float inv_sw = 1 / sw;
  const float spread = spp - length2(sp) * inv_sw;  // Σw‖y − ȳ‖² ≥ 0
  s.u4 = spread > 1e-6f * sw ? 0.5f * (spn - glm::dot(sp, sn) * inv_sw) / spread : 0.0f;
  s.u = (sn - 2 * s.u4 * sp) * inv_sw;
  s.u0 = -(glm::dot(s.u, sp) + s.u4 * spp) * inv_sw;
  s.valid = length2(s.u) > 0;
  return s;
}

// The point of the sphere's zero set nearest `origin` (y = 0). It lies on the line through
// the centre, which is the gradient's line u at y = 0: f(s·û) = u0 + s‖u‖ + u4 s² = 0, whose
// root of least magnitude −2u0/(‖u‖ + √(‖u‖² − 4u0u4)) has no cancellation and tends to the
// plane's −u0/‖u‖ as u4 → 0 (no centre to compute far away). False where the sphere is
// imaginary (negative discriminant).
PSS_INLINE bool nearest_on_sphere(const AlgebraicSphere& s, vec3& y) {
  const float g = glm::length(s.u);
  const float disc = g * g - 4 * s.u0 * s.u4;
  if (!(g > 0) || !(disc >= 0)) return false;
  const float step = -2 * s.u0 / (g + sqrt(disc));
  y = (step / g) * s.u;
  return true;
}

// APSS's projection (project_by_fits): x → the point of the sphere fitted at x nearest x.
// The frame sits there with the normal ∇f/‖∇f‖ (oriented as the samples' normals), and the
// polynomial is the sphere's osculating paraboloid: f(y* + (a, b, z)) ≈ ‖∇f‖z + u4(a² + b²)
// = 0 to second order.
template <class Samples>
PSS_HOST_DEVICE Projection project_apss(const Samples& samples, vec3 r, const ProjectionParams& params,
                                        vec3 normal_hint, int steps) {
  return project_by_fits(samples, r, params, normal_hint, steps, [&](vec3& x, float h, Projection& out) {
    const AlgebraicSphere s = fit_algebraic_sphere(samples, x, h);
    vec3 y;
    if (!s.valid || !nearest_on_sphere(s, y)) return -1.0f;
    const vec3 g = s.gradient_at(y);
    const float g_norm = glm::length(g);
    const vec3 next = x + h * y;
    out.normal = g / g_norm;
    out.frame = Frame::from_normal(next, out.normal);
    const float curvature = -s.u4 / (g_norm * h);  // z = curvature·(a² + b²), world units
    out.polynomial = Polynomial{curvature, curvature, 0.0f, 0.0f};
    const float moved = glm::length(next - x);
    x = next;
    return moved;
  });
}

}  // namespace pss
