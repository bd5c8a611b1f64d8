// The "Initial approximation" of paper §5.2, computed once per cloud: at every sample p_i
// the covariance normal n_i of its neighbourhood N(p_i) and the WLS polynomial g_i in the frame
// (p_i, n_i), with t = 0 "since the point to be projected is the sample point itself, and
// is thus near the PSS". Rays meet these polynomials first, each inside its ball B(p_i, b_i).
#pragma once

#include "pss/core/frame.hpp"
#include "pss/fit/inverse_power.hpp"
#include "pss/fit/polynomial.hpp"
#include "pss/points/neighbourhood.hpp"

namespace pss {

// 48 bytes, what the ray tests read first (centre, slab, normal, ball) up front: the BVH leaves
// touch many of these per ray, so they are kept small; the tangent axes are rebuilt from the
// normal (Frame::from_normal, the same arithmetic as when g was fitted) only for the few
// that pass the ball and slab tests.
struct LocalPolynomial {
  vec3 origin;  // p_i
  // A bound on |g| over the disc x² + y² ≤ b_i², plus the rounding of p_i's coordinates: the
  // graph inside the ball lies in the slab |z| ≤ height, a cheap test that spares most rays
  // the quadratic (height_bound, coordinate_rounding).
  float height = kInfinity;
  vec3 normal;  // n_i
  float radius = 0;  // b_i, the ball's: b at h, scaled with the sample's width h_i
  Polynomial g;

  PSS_HOST_DEVICE Frame frame() const { return Frame::from_normal(origin, normal); }
};

// |Ax² + By² + Cxy + D| ≤ |D| + (|A| + |B| + |C|/2)·b² where x² + y² ≤ b², as x², y² ≤ b²
// and |xy| ≤ b²/2.
PSS_INLINE float height_bound(const Polynomial& g, float b) {
  return abs(g.d) + (abs(g.a) + abs(g.b) + 0.5f * abs(g.c)) * b * b;
}

// A bound on the rounding of heights computed from world coordinates of p's size (~1e-7 of
// |p|₁, with room). The slab |z| ≤ height of a planar sample is otherwise no thicker than
// that rounding, and whether a rounded ray enters it is chance (an FMA decides otherwise):
// PreparedCloud adds it for the sample to LocalPolynomial::height, nearest_local_hit for
// the ray's origin.
PSS_INLINE float coordinate_rounding(vec3 p) { return 1e-6f * (abs(p.x) + abs(p.y) + abs(p.z)); }

enum class LocalFitStatus : unsigned char {
  ok,
  degenerate_normal,   // neighbours (nearly) on a line: the normal is not defined by the data
  too_few_neighbours,  // fewer than 3 samples in N(p_i): no surface here, the sample is left out
};

struct LocalFit {
  LocalPolynomial local;
  LocalFitStatus status;
};

// The per-sample kernel both backends run, for the grid's sorted sample i. `hint` (the
// file's normal, or zero) only orients n_i; the covariance decides it. b_i = ball_per_h·h_i.
PSS_INLINE LocalFit fit_local_polynomial(const SupportGridView& grid, int i, vec3 hint, float ball_per_h) {
  // t = 0: the plane passes through p itself, so the covariance is taken about p (the
  // paper's C(q) with q = p), not about the weighted mean.
  const vec3 p = grid.points[i];
  const float h = 1.0f / sqrt(grid.inv_h2[i]);
  const Neighbourhood near(grid, p);
  const WeightedMoments moments = near.moments();
  LocalFit out;
  out.local.origin = p;
  out.local.radius = ball_per_h * h;
  out.local.normal = vec3(0, 0, 1);
  if (moments.count < 3 || !(moments.weight_sum > 0)) {
    out.status = LocalFitStatus::too_few_neighbours;
    return out;
  }
  const EigenResult eig = smallest_eigenvector(moments.covariance_about_origin(), hint);
  const Frame frame = Frame::from_normal(p, eig.vector);
  out.local.normal = frame.n;
  out.local.g = near.polynomial_fit(frame, false, h).solve();
  out.status = eig.status == EigenStatus::degenerate || eig.status == EigenStatus::invalid
                   ? LocalFitStatus::degenerate_normal
                   : LocalFitStatus::ok;
  return out;
}

// out[i] = the local polynomial of the grid's sorted sample i (backend/parallel_for.hpp).
struct FitLocalPolynomialsKernel {
  SupportGridView grid;
  const vec3* hints;  // in the grid's order
  LocalFit* out;
  float ball_per_h;  // b/h
  PSS_HOST_DEVICE void operator()(std::int64_t i) const {
    out[i] = fit_local_polynomial(grid, int(i), hints[i], ball_per_h);
  }
};

}  // namespace pss
