// `pss mesh` tile by tile (issue 28): the piece of a cloud's mesh in a box of the lattice's
// cubes, from the samples of a tile and its halo. Pieces of neighbouring boxes meet on the
// same vertices (mesh/weld.hpp joins them): each piece is marched kPieceMargin cubes past its
// box, and the halo holds every sample that a corner there reads, so the corners, the roots on
// the edges and the crease fans of the cubes they share are the same in both.
#pragma once

#include <vector>

#include "pss/backend/backend.hpp"
#include "pss/mesh/marching_tetrahedra.hpp"
#include "pss/points/projection.hpp"
#include "pss/spatial/support_grid.hpp"

namespace pss {

// Cubes a piece is marched past its box on every side: a crease fan's flips reach the next
// cube, and the band grows into a box through its neighbours' cubes.
inline constexpr int kPieceMargin = 3;

struct CloudMeshPiece {
  MarchedPiece piece;
  std::vector<float> cell;  // each vertex's, for the coarsening (mesh_cloud.cpp)
  MarchCounts counts;       // its cubes_crossed the box's own
};

// The piece in `kept` of the mesh of the PSS of `grid`'s samples, whose oriented normals it
// holds, seeded at every sample, with `params` (the projection's) and `crease_angle`; each
// vertex's cell `asked`, or kDefaultCellPerH of its nearest covering sample's width, at least
// `least` (as mesh_cloud).
CloudMeshPiece mesh_cloud_piece(const SupportGrid& grid, const ProjectionParams& params, const Lattice& lattice,
                                const CubeBox& kept, float crease_angle, float asked, float least, Backend backend);

}  // namespace pss
