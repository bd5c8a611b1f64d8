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

// The implicit of the kernels (implicit_kernels.hpp) for the samples of `grid`.
struct CloudImplicit {
  SupportGridView grid;
  ProjectionParams params;
  PSS_HOST_DEVICE SignedDistance operator()(vec3 x) const { return signed_distance(grid, x, params); }
};

}  // namespace pss
