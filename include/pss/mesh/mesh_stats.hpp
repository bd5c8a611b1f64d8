// What --stats (and the Python module's full_output) records of every mesh: its shape and
// its band (issue 27).
#pragma once

#include "pss/core/stats.hpp"
#include "pss/mesh/marching_tetrahedra.hpp"
#include "pss/mesh/mesh_cloud.hpp"
#include "pss/mesh/triangle_mesh.hpp"

namespace pss {

// "mesh": the shape's counts and whether it is watertight and manifold; "band": the march's
// counts (corners, cubes visited, meshed and refused, the crease, pinch and turn steps').
void record_mesh(Stats& stats, const MeshTopology& shape, const MarchCounts& counts);

// All of a cloud's mesh: its surface (points/surface_stats.hpp) with the cell, crease angle
// and borders among the parameters, record_mesh, and "turned_outward".
void record_cloud_mesh(Stats& stats, const CloudMesh& made, const MeshParams& params, const MeshTopology& shape);

}  // namespace pss
