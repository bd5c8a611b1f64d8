// The mesh of a volume's PSS (`pss mesh` of a volume, issue 27): marching tetrahedra
// (mesh/marching_tetrahedra.hpp) over the cubes near the cells the surface crosses, of the
// signed distance to the paper's projection (mesh/volume_implicit.hpp), every vertex a root
// of it on its edge with the fitted surface's normal there: iso (θ1) or gradient (θ2)
// surfaces, by the predictor or the predictor-corrector, as `pss volume` draws them.
#pragma once

#include "pss/backend/backend.hpp"
#include "pss/core/stats.hpp"
#include "pss/mesh/marching_tetrahedra.hpp"
#include "pss/volume/prepared.hpp"

namespace pss {

// The cubes' side, in voxels u (VolumeView::voxel_size), where none is given: the data
// resolve nothing finer, and marching cubes' meshes have about one vertex per voxel too.
inline constexpr float kDefaultCellVoxels = 1.0f;

struct VolumeMesh {
  TriangleMesh mesh;
  MarchCounts counts;
  float cell = 0;
};

// `cell` in world units, 0 for kDefaultCellVoxels. Faces outward: towards lower values.
// Throws Error for a cell that is not a positive number or too small for the surface
// (band_cube_limit), and where the surface gives no triangle.
VolumeMesh mesh_volume(const PreparedVolume& volume, float cell, Backend backend, Stats& stats);

}  // namespace pss
