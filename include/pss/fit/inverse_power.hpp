// The normal as the eigenvector of the smallest eigenvalue of a weighted covariance matrix,
// found by the inverse power method (paper §4, §5.2; Numerical Recipes §11.7).
//
// We iterate with A = C + s·I, s = 1e-5·tr(C), instead of C itself: a planar neighbourhood
// makes C singular exactly where we need it, and the shift keeps A positive definite while
// changing no eigenvector. Each step solves A y = x by Cholesky.
#pragma once

#include "pss/fit/moments.hpp"

namespace pss {

enum class EigenStatus : unsigned char {
  converged,
  // Two smallest eigenvalues (nearly) equal: a linear or point-like neighbourhood, so the
  // normal is not defined by the data. The vector returned is the one in that eigenspace
  // closest to the start vector.
  degenerate,
  not_converged,
  invalid,  // zero or non-finite matrix: the start vector is returned unchanged
};

struct EigenResult {
  vec3 vector;
  float eigenvalue;  // Rayleigh quotient xᵀCx
  EigenStatus status;
  int iterations;
};

namespace detail {

// Cholesky factor of a symmetric positive definite 3×3 matrix; false if not SPD.
struct Cholesky3 {
  float l00, l10, l11, l20, l21, l22;
  float r00, r11, r22;  // 1/l00, 1/l11, 1/l22: solve() multiplies, each step of the power
                        // iteration then waits on no division

  PSS_HOST_DEVICE bool factor(const Sym3& a) {
    if (!(a.xx > 0)) return false;
    l00 = sqrt(a.xx);
    r00 = 1.0f / l00;
    l10 = a.xy * r00;
    l20 = a.xz * r00;
    const float d1 = a.yy - l10 * l10;
    if (!(d1 > 0)) return false;
    l11 = sqrt(d1);
    r11 = 1.0f / l11;
    l21 = (a.yz - l20 * l10) * r11;
    const float d2 = a.zz - l20 * l20 - l21 * l21;
    if (!(d2 > 0)) return false;
    l22 = sqrt(d2);
    r22 = 1.0f / l22;
    return true;
  }
  PSS_HOST_DEVICE vec3 solve(vec3 b) const {
    const float y0 = b.x * r00;
    const float y1 = (b.y - l10 * y0) * r11;
    const float y2 = (b.z - l20 * y0 - l21 * y1) * r22;
    const float x2 = y2 * r22;
    const float x1 = (y1 - l21 * x2) * r11;
    const float x0 = (y0 - l10 * x1 - l20 * x2) * r00;
    return vec3(x0, x1, x2);
  }
};

// Largest column of adj(C): for a rank-2 (planar) C it is parallel to the normal, and for a
// full-rank C it is det(C)·C⁻¹eᵢ, one inverse step from a unit vector.
PSS_INLINE vec3 adjugate_start(const Sym3& c) {
  const vec3 c0(c.yy * c.zz - c.yz * c.yz, c.xz * c.yz - c.xy * c.zz, c.xy * c.yz - c.xz * c.yy);
  const vec3 c1(c0.y, c.xx * c.zz - c.xz * c.xz, c.xy * c.xz - c.xx * c.yz);
  const vec3 c2(c0.z, c1.z, c.xx * c.yy - c.xy * c.xy);
  const float n0 = length2(c0), n1 = length2(c1), n2 = length2(c2);
  if (n0 >= n1 && n0 >= n2) return c0;
  return n1 >= n2 ? c1 : c2;
}

}  // namespace detail

// Eigenvalue gaps below this fraction of the trace leave the normal undefined.
inline constexpr float kDegenerateGap = 1e-2f;

// `start` orients the result (xᵀstart ≥ 0) and decides the answer in degenerate cases;
// pass a zero vector when nothing is known.
PSS_INLINE EigenResult smallest_eigenvector(const Sym3& c, vec3 start, int max_iterations = 32,
                                            float tolerance = 1e-6f) {
  const float tr = c.trace();
  const vec3 fallback = length2(start) > 0 ? glm::normalize(start) : vec3(0, 0, 1);
  if (!(tr > 0) || !is_finite(tr)) return {fallback, 0.0f, EigenStatus::invalid, 0};

  // Work on C/tr: eigenvalues in [0, 1] summing to 1, whatever the units of the data.
  const Sym3 cn = c.scaled(1.0f / tr);
  Sym3 a = cn;
  const float shift = 1e-5f;
  a.xx += shift;
  a.yy += shift;
  a.zz += shift;
  detail::Cholesky3 chol;
  if (!chol.factor(a)) return {fallback, 0.0f, EigenStatus::invalid, 0};

  vec3 x = length2(start) > 0 ? start : detail::adjugate_start(cn);
  if (!(length2(x) > 0)) x = vec3(0, 0, 1);
  x = glm::normalize(x);

  EigenStatus status = EigenStatus::not_converged;
  int it = 0;
  while (it < max_iterations) {
    ++it;
    vec3 y = chol.solve(x);
    const float len = glm::length(y);
    if (!(len > 0) || !is_finite(len)) break;
    y *= 1.0f / len;
    if (glm::dot(y, x) < 0) y = -y;  // the sign is free; keep it steady to measure the change
    const float change = length2(y - x);
    x = y;
    if (change < tolerance * tolerance) {
      status = EigenStatus::converged;
      break;
    }
  }
  if (length2(start) > 0 && glm::dot(x, start) < 0) x = -x;

  // The gap λ1 − λ0 decides whether the data define a normal at all. With λ0 the Rayleigh
  // quotient of C/tr, λ1 and λ2 are the roots of λ² − (1 − λ0)λ + (I2 − λ0(1 − λ0)), I2 the
  // second invariant. Within a (near) double eigenvalue the iteration drifts with rounding
  // and never settles, so degeneracy is judged here, not by convergence.
  const float i2 = (cn.xx * cn.yy - cn.xy * cn.xy) + (cn.xx * cn.zz - cn.xz * cn.xz) + (cn.yy * cn.zz - cn.yz * cn.yz);
  const float lambda0 = glm::dot(x, cn * x);
  const float rest = 1.0f - lambda0;
  const float lambda1 = 0.5f * (rest - sqrt(max(0.0f, rest * rest - 4.0f * (i2 - lambda0 * rest))));
  if (lambda1 - lambda0 < kDegenerateGap) status = EigenStatus::degenerate;
  return {x, lambda0 * tr, status, it};
}

}  // namespace pss
