// The implicit of a cloud's PSS that `pss mesh` contours (issue 27), on either backend: at x,
// the signed distance along the fitted normal to the projection P(x),
//   f(x) = (x − P(x))·n(P(x)),
// with n turned to the side of the oriented normal of the sample nearest P(x), so that
// f > 0 outside. f = 0 exactly where x = P(x): where x lies on the PSS, of any surface operator.
#pragma once

#include <cstdint>

#include "pss/mesh/marching_tetrahedra.hpp"
#include "pss/points/surface_projection.hpp"

namespace pss {

struct SignedDistance {
  float distance;
  vec3 surface_point, normal;
  bool valid;  // a projection with neighbours, inside the samples where borders are clipped
};

// The oriented normal of the sample nearest x among those whose support holds it; zero
// where none does. Near a thin part both sides' samples hold x, with opposed normals, and
// any average of them cancels: the nearest sample's side is the side x is on.
PSS_INLINE vec3 nearest_normal(const SupportGridView& grid, vec3 x) {
  const int nearest = grid.nearest_covering(x);
  return nearest < 0 ? vec3(0.0f) : grid.normals[nearest];
}

// The projection from x starts at the nearest sample's oriented normal, and its normal is
// turned to the side of the sample nearest P(x): at the surface point, not at x, which may
// lie nearer the other side's samples of a thin part than the side it projects to (the
// bunny's ears: at x, 5 components and twice the boundary edges).
PSS_INLINE SignedDistance signed_distance(const SupportGridView& grid, vec3 x, const ProjectionParams& params) {
  const vec3 hint = nearest_normal(grid, x);
  if (!(length2(hint) > 0)) return {0.0f, x, vec3(0.0f), false};
  const Projection p = project_onto_surface(grid, x, params, hint);
  const vec3 outside = nearest_normal(grid, p.point);
  const bool valid = (p.status == ProjectionStatus::converged || p.status == ProjectionStatus::not_converged) &&
                     p.surrounded && is_finite(p.point) && length2(outside) > 0;
  const vec3 n = glm::dot(p.normal, outside) < 0 ? -p.normal : p.normal;
  return {glm::dot(x - p.point, n), p.point, n, valid};
}

// out[i] = the implicit at corners[i].
struct SampleCornersKernel {
  SupportGridView grid;
  const vec3* corners;
  CornerSample* out;
  ProjectionParams params;
  PSS_HOST_DEVICE void operator()(std::int64_t i) const {
    const SignedDistance s = signed_distance(grid, corners[i], params);
    out[i] = {s.distance, s.surface_point, s.valid};
  }
};

// A vertex strictly inside its edge, no nearer an end than this share of the edge, so that
// no triangle degenerates where the surface passes through or near a corner. At 10⁻³ such
// slivers meet their neighbours at angles of 10⁻³ that the common checkers' tolerances
// take for crossings (Open3D: 14 pairs of a sphere's 23,384 triangles, 7 at 3·10⁻³, none at
// 10⁻²), though in exact arithmetic on the written floats none cross. Where the surface
// passes that near a corner its vertex lies off it by at most this share of its edge.
inline constexpr float kEdgeMargin = 1e-2f;

// out[i] = the root of f on edges[i], by regula falsi (each step a projection; the bracket
// keeps the root on the edge), until |f| <= tolerance or `steps` projections; the normal is
// the PSS's at the root. f is nearly linear along an edge, so the secant lands close: 1.95
// projections per vertex on the bunny, 2.33 on hippo1 (Illinois's rule, which keeps an end
// from sticking, measured no fewer).
struct CrossEdgesKernel {
  SupportGridView grid;
  const EdgeCrossing* edges;
  MeshVertex* out;
  ProjectionParams params;
  float tolerance;
  int steps;
  PSS_HOST_DEVICE void operator()(std::int64_t i) const {
    const EdgeCrossing e = edges[i];
    float lo = 0, hi = 1, f_lo = e.distance_a, f_hi = e.distance_b;
    float t = f_lo / (f_lo - f_hi);
    vec3 normal(0.0f);
    for (int k = 0; k < steps; ++k) {
      t = min(max(t, kEdgeMargin), 1 - kEdgeMargin);
      const SignedDistance s = signed_distance(grid, e.a + t * (e.b - e.a), params);
      if (!s.valid) break;
      normal = s.normal;
      if (abs(s.distance) <= tolerance) break;
      if ((s.distance < 0) == (f_lo < 0)) {
        lo = t;
        f_lo = s.distance;
      } else {
        hi = t;
        f_hi = s.distance;
      }
      t = lo + (hi - lo) * (f_lo / (f_lo - f_hi));
    }
    t = min(max(t, kEdgeMargin), 1 - kEdgeMargin);
    if (!(length2(normal) > 0)) normal = glm::normalize(e.distance_a < 0 ? e.b - e.a : e.a - e.b);
    out[i] = {e.a + t * (e.b - e.a), normal};
  }
};

}  // namespace pss
