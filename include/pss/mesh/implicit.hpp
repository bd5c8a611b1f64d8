// What marching asks of an implicit surface (issue 27): its signed distance and side at the
// band's corners, and the roots on the edges its sign changes across, in batches, on
// whichever backend runs it (mesh/implicit_kernels.hpp). A contract between the march and
// the implicits of clouds and volumes, below both.
#pragma once

#include <functional>
#include <span>

#include "pss/core/progress.hpp"
#include "pss/core/types.hpp"

namespace pss {

// What the implicit says at a corner: its signed distance to the surface (positive
// outside, where the surface's normals point), a point of the surface near it (where the
// band grows to) unless it knows only the corner's side, and whether the distance can be
// trusted (no surface there: no triangles).
struct CornerSample {
  float distance = 0;
  vec3 surface_point{0.0f};
  bool valid = false;
  bool on_surface = true;  // surface_point lies on the surface; false: the band does not grow there
  bool side_from_data = false;  // the data put the corner on this side (marching_tetrahedra.hpp)
};

// An edge whose ends' signs differ (distance_a < 0 <= distance_b or the reverse), and the
// vertex found on it: its position on the edge, strictly between the ends, and the
// surface's unit normal there.
struct EdgeCrossing {
  vec3 a, b;
  float distance_a, distance_b;
};
struct MeshVertex {
  vec3 position, normal;
};

// The implicit, evaluated in batches (on whichever backend the caller runs). A batch of
// corners advances the caller's `progress` (the band's, over its waves; the creases' own).
struct ImplicitSurface {
  std::function<void(std::span<const vec3> corners, std::span<CornerSample> out, Progress& progress)> sample;
  std::function<void(std::span<const EdgeCrossing> edges, std::span<MeshVertex> out)> cross;
};

}  // namespace pss
