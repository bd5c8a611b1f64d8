// Brent's one-dimensional minimisation using first derivatives (Numerical Recipes §10.3,
// "dbrent"), used by the MLS plane fit (Eq. 2) and the corrector (Eq. 4) to minimise the
// energy along the normal. f(x, df) returns f(x) and writes f'(x).
#pragma once

#include "pss/core/platform.hpp"

namespace pss {

struct BrentResult {
  float x;
  float fx;
  int evaluations;
};

// Minimises f over [lo, hi], starting from x0 in that interval, to an absolute tolerance
// (callers know the length scale h). The derivative's sign picks which part of the interval
// to search; secant steps on the derivative give superlinear convergence, bisection keeps
// it safe.
template <class F>
PSS_HOST_DEVICE BrentResult brent_minimize(F&& f, float lo, float hi, float x0, float tolerance,
                                           int max_iterations = 32) {
  float a = lo, b = hi;
  float x = x0, w = x0, v = x0;
  float dx;
  float fx = f(x, dx);
  float fw = fx, fv = fx, dw = dx, dv = dx;
  float d = 0, e = 0;
  int evaluations = 1;
  for (int it = 0; it < max_iterations; ++it) {
    const float xm = 0.5f * (a + b);
    const float tol1 = tolerance;
    const float tol2 = 2 * tol1;
    if (abs(x - xm) <= tol2 - 0.5f * (b - a)) break;
    bool bisect = true;
    if (abs(e) > tol1) {
      // Secant steps on f' from the two best points, kept if they fall inside [a, b] and
      // go downhill.
      float d1 = 2 * (b - a), d2 = d1;
      if (dw != dx) d1 = (w - x) * dx / (dx - dw);
      if (dv != dx) d2 = (v - x) * dx / (dx - dv);
      const float u1 = x + d1, u2 = x + d2;
      const bool ok1 = (a - u1) * (u1 - b) > 0 && dx * d1 <= 0;
      const bool ok2 = (a - u2) * (u2 - b) > 0 && dx * d2 <= 0;
      const float olde = e;
      e = d;
      if (ok1 || ok2) {
        const float step = (ok1 && ok2) ? (abs(d1) < abs(d2) ? d1 : d2) : (ok1 ? d1 : d2);
        if (abs(step) <= abs(0.5f * olde)) {
          d = step;
          const float u = x + d;
          if (u - a < tol2 || b - u < tol2) d = copysign(tol1, xm - x);
          bisect = false;
        }
      }
    }
    if (bisect) {
      e = dx >= 0 ? a - x : b - x;
      d = 0.5f * e;
    }
    const float u = abs(d) >= tol1 ? x + d : x + copysign(tol1, d);
    float du;
    const float fu = f(u, du);
    ++evaluations;
    if (abs(d) < tol1 && fu > fx) break;  // the minimum is within tol1 of x
    if (fu <= fx) {
      if (u >= x) a = x; else b = x;
      v = w; fv = fw; dv = dw;
      w = x; fw = fx; dw = dx;
      x = u; fx = fu; dx = du;
    } else {
      if (u < x) a = u; else b = u;
      if (fu <= fw || w == x) {
        v = w; fv = fw; dv = dw;
        w = u; fw = fu; dw = du;
      } else if (fu < fv || v == x || v == w) {
        v = u; fv = fu; dv = du;
      }
    }
  }
  return {x, fx, evaluations};
}

}  // namespace pss
