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
// (surface_cells.hpp), f is as above. Where it does not, there is no surface of the data
// near x: the fit may draw a sheet along a dip of the values that never reaches v (inside a
// tooth's dentine, say), which rendering rejects point by point; a mesh needs every
// corner's side, or the real surface beside such a sheet breaks open where its cubes'
// corners project onto the sheet. Of an iso-surface the data say which side x is on: there
// f is the first-order distance (v − f(x))/|∇f(x)|, clamped to the neighbourhood's radius,
// and the band does not grow from x. Beyond the box, or of a gradient surface, such a
// corner is not valid.
struct VolumeImplicit {
  VolumeScene scene;
  PSS_HOST_DEVICE SignedDistance operator()(vec3 x) const {
    const VolumeParams& p = scene.params;
    const FieldView& fields = scene.fields;
    VoxelScratch nb;
    const VolumeProjection proj = project_volume_point(fields, p, x, nb);
    const vec3 n = -proj.normal;
    if (proj.status == VolumeProjectionStatus::ok && is_finite(proj.point) &&
        is_data_surface(fields, scene.cells, scene.feature, proj.point, proj.normal, p.surface_reach()))
      return {glm::dot(x - proj.point, n), proj.point, n, true};
    const Aabb box = fields.volume.bounds();
    const vec3 g = fields.gradient_at(x);
    if (scene.feature.kind != FeatureKind::iso || !box.contains(x) || !(length2(g) > 0))
      return {0.0f, x, vec3(0.0f), false};
    const float length = glm::length(g);
    const float distance = (scene.feature.iso - sample(fields.volume, x)) / length;
    return {clamp(distance, -p.radius, p.radius), x, -g / length, true, false};
  }
};

}  // namespace pss
