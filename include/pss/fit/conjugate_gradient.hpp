// Conjugate gradient for the 4×4 normal equations of the polynomial fit (paper §5.2,
// Numerical Recipes §2.7). In exact arithmetic CG ends in at most 4 steps; started from
// zero on a singular but consistent system (collinear neighbours) it still converges, to
// the minimum-norm solution, where a direct inverse would divide by zero.
#pragma once

#include <glm/mat4x4.hpp>

#include "pss/core/types.hpp"

namespace pss {

struct CgResult {
  vec4 x;
  int iterations;
};

// Solves M x = b for symmetric positive semi-definite M. The system is first scaled
// symmetrically by its diagonal (Jacobi), which leaves the solution unchanged and makes
// the scales of x², y², xy and 1 comparable.
PSS_INLINE CgResult conjugate_gradient(const glm::mat4& m, vec4 b, int max_iterations = 8,
                                       float relative_tolerance = 1e-6f) {
  vec4 d;
  for (int i = 0; i < 4; ++i) d[i] = m[i][i] > 0 ? 1.0f / sqrt(m[i][i]) : 0.0f;
  glm::mat4 a;
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) a[c][r] = m[c][r] * d[c] * d[r];
  const vec4 bs = b * d;

  vec4 y(0.0f);
  vec4 res = bs;
  vec4 p = res;
  float rr = glm::dot(res, res);
  const float stop = relative_tolerance * relative_tolerance * rr;
  int it = 0;
  while (it < max_iterations && rr > stop) {
    const vec4 ap = a * p;
    const float pap = glm::dot(p, ap);
    if (!(pap > 0)) break;  // p lies in the null space: nothing left to reduce
    const float alpha = rr / pap;
    y += alpha * p;
    res -= alpha * ap;
    const float rr_next = glm::dot(res, res);
    p = res + (rr_next / rr) * p;
    rr = rr_next;
    ++it;
  }
  return {y * d, it};
}

}  // namespace pss
