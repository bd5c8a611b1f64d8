// The implicit of a cloud's PSS that `pss mesh` contours (issue 27), on either backend: at x,
// the signed distance along the fitted normal to the projection P(x) (implicit_kernels.hpp),
//   f(x) = (x − P(x))·n(P(x)),
// with n turned to the side of the oriented normal of the sample nearest P(x), so that
// f > 0 outside. f = 0 exactly where x = P(x): where x lies on the PSS, of any surface operator.
// Valid where the projection has neighbours, inside the samples where borders are clipped.
#pragma once

#include <cstdint>

#include "pss/mesh/implicit_kernels.hpp"
#include "pss/points/surface_projection.hpp"

namespace pss {

// The oriented normal of the sample nearest x among those whose support holds it; zero
// where none does. Near a thin part both sides' samples hold x, with opposed normals, and
// any average of them cancels: the nearest sample's side is the side x is on.
PSS_INLINE vec3 nearest_normal(const SupportGridView& grid, vec3 x) {
  const int nearest = grid.nearest_covering(x);
  return nearest < 0 ? vec3(0.0f) : grid.normals[nearest];
}

// A sample whose normal lies within 75° of ±n (|cos| >= 1/4) can say which way n faces; one
// nearer 90° lies across a crease, and the sign of its normal's dot with n is noise. One
// more than 105° from n (the other sheet of a thin part) faces away from n.
inline constexpr float kFacesTheSameWay = 0.25f;

// The oriented normal of the sample nearest x among those whose support holds it and whose
// normal lies along ±n (kFacesTheSameWay), or where none does, of the nearest of them all;
// zero where none holds x.
PSS_INLINE vec3 normal_along(const SupportGridView& grid, vec3 x, vec3 n) {
  float nearest = kInfinity, nearest_along = kInfinity;
  vec3 normal(0.0f), along(0.0f);
  grid.for_each_covering(x, [&](vec3, float d2, int i) {
    if (d2 < nearest) {
      nearest = d2;
      normal = grid.normals[i];
    }
    if (d2 < nearest_along && abs(glm::dot(grid.normals[i], n)) >= kFacesTheSameWay) {
      nearest_along = d2;
      along = grid.normals[i];
    }
  });
  return nearest_along < kInfinity ? along : normal;
}

// x's signed distance to P(x) on the surface with the oriented normal n there: along the
// normal, among n and those of the samples whose support holds P(x) and that do not face
// away from n, along which x lies farthest from P(x). Where P(x) is on a crease, n may be
// either face's, and x, off the other face, lies along n nowhere near as far as it is from
// the surface, or even on the wrong side (a box's edges: f < 0 up to 0.02 outside, and
// bubbles there).
PSS_INLINE float distance_across(const SupportGridView& grid, vec3 x, vec3 surface_point, vec3 n) {
  const vec3 d = x - surface_point;
  float distance = glm::dot(d, n);
  grid.for_each_covering(surface_point, [&](vec3, float, int i) {
    const float along = glm::dot(d, grid.normals[i]);
    if (glm::dot(grid.normals[i], n) > -kFacesTheSameWay && abs(along) > abs(distance)) distance = along;
  });
  return distance;
}

// The projection from x starts at the nearest sample's oriented normal, and its normal is
// turned to the side of the sample nearest P(x) that lies along it: at the surface point,
// not at x, which may lie nearer the other side's samples of a thin part than the side it
// projects to (the bunny's ears: at x, 5 components and twice the boundary edges); and not
// a sample across a crease, whose normal is nearly perpendicular (a box's edges: thin
// sheets of the wrong sign standing off its faces).
PSS_INLINE SignedDistance signed_distance(const SupportGridView& grid, vec3 x, const ProjectionParams& params) {
  const vec3 hint = nearest_normal(grid, x);
  if (!(length2(hint) > 0)) return {0.0f, x, vec3(0.0f), false};
  const Projection p = project_onto_surface(grid, x, params, hint);
  const vec3 outside = normal_along(grid, p.point, p.normal);
  const bool valid = (p.status == ProjectionStatus::converged || p.status == ProjectionStatus::not_converged) &&
                     p.surrounded && is_finite(p.point) && length2(outside) > 0;
  const vec3 n = glm::dot(p.normal, outside) < 0 ? -p.normal : p.normal;
  return {distance_across(grid, x, p.point, n), p.point, n, valid};
}

// The implicit of the kernels (implicit_kernels.hpp) for the samples of `grid`.
struct CloudImplicit {
  SupportGridView grid;
  ProjectionParams params;
  PSS_HOST_DEVICE SignedDistance operator()(vec3 x) const { return signed_distance(grid, x, params); }
  // A mesh vertex's normal, from its last projection s: the one `pss project` reports there.
  PSS_HOST_DEVICE vec3 vertex_normal(const SignedDistance& s) const {
    return reported_normal(grid, s.surface_point, s.normal, params);
  }
};

}  // namespace pss
