// The implicit of a volume's PSS that `pss mesh` contours (issue 27), on either backend: at x,
// the signed distance to the paper's projection γ(x) (§5.1: the predictor, Eq. 3, then the
// corrector, Eq. 4, as the method asks) along the fitted surface's outward normal,
//   f(x) = (x − γ(x))·n,  n = −∇f/|∇f| there,
// outward being towards lower values: the material above the iso-value, or on the high side
// of a gradient surface's step, is inside (as marching cubes' meshes and VTK's have it).
// f = 0 exactly where γ(x) = x: the points that ray marching and `pss extract` accept.
#pragma once

#include "pss/mesh/implicit_kernels.hpp"
#include "pss/volume/marcher.hpp"

namespace pss {

// Where the projection converges onto a point where the data have a surface
// (surface_cells.hpp), within two cube sides of x, f is as above. Where it does not, there is
// no surface of the PSS that the data back near x: the fit may draw a sheet along a dip of
// the values that never reaches v (inside a tooth's dentine, say), or smooth away a void a
// voxel wide that the data have; rendering rejects such points one by one, but a mesh needs
// every corner's side, or the surface breaks open where its cubes' corners project onto such
// a sheet. And a corner of a cube the surface crosses lies within a cube's diagonal (√3
// sides) of it: a projection that walked farther went to another sheet (on thick slices, a
// neighbourhood long across them carries the predictor's steps several voxels away), and its
// distance beside a neighbour's near one made the cube a jump, a hole in the mesh. Of an
// iso-surface the data say which side x is on: there f is the first-order distance
// (v − f(x))/|∇f(x)| (the cube's side where f is flat), at most the cube's side
// (`side_reach`), and its side is the data's, so that the change of sign it makes with a
// neighbour is meshed, never taken for a jump (marching_tetrahedra.hpp): the data cross v
// between them. The band does not grow from x. Beyond the box, or of a gradient surface,
// such a corner is not valid. A projection's side is the data's too wherever they agree: in
// a noisy plateau at v (the tooth's enamel at 230) two neighbours' projections may land on
// different sheets a side or two away, with the data crossing v between them. Where they
// disagree, f is the PSS's within a side of its sheet (it smooths the data); beyond, the
// projection went past the sheet nearest x, and the data's side is taken, as above.
inline constexpr float kProjectionReachSides = 2.0f;  // beyond √3: a cube's diagonal

struct VolumeImplicit {
  VolumeScene scene;
  float side_reach;  // the cube's side
  PSS_HOST_DEVICE SignedDistance operator()(vec3 x) const {
    const FieldView& fields = scene.fields;
    VoxelScratch nb;
    const VolumeProjection proj = project_volume_point(fields, scene.params, x, nb);
    const vec3 n = -proj.normal;
    const float reach = kProjectionReachSides * side_reach;
    const bool sided = scene.feature.kind == FeatureKind::iso && fields.volume.bounds().contains(x);
    const float difference = sided ? scene.feature.iso - sample(fields.volume, x) : 0.0f;
    if (proj.status == VolumeProjectionStatus::ok && is_finite(proj.point) &&
        length2(x - proj.point) <= reach * reach &&
        is_data_surface(fields, scene.cells, scene.feature, proj.point, proj.normal, scene.params.surface_reach())) {
      const float distance = glm::dot(x - proj.point, n);
      const bool agrees = sided && (difference < 0) == (distance < 0);
      if (!sided || agrees || abs(distance) <= side_reach) return {distance, proj.point, n, true, true, agrees};
    }
    if (!sided) return {0.0f, x, vec3(0.0f), false};
    const vec3 g = fields.gradient_at(x);
    const float length = glm::length(g);
    if (!(length > 0))  // flat (saturated) data: no gradient, no projection, but a side
      return {difference > 0 ? side_reach : difference < 0 ? -side_reach : 0.0f, x, vec3(0.0f), true, false, true};
    return {clamp(difference / length, -side_reach, side_reach), x, -g / length, true, false, true};
  }
  // A mesh vertex's normal, from its last projection s.
  PSS_HOST_DEVICE vec3 vertex_normal(const SignedDistance& s) const { return s.normal; }
};

}  // namespace pss
