// A marched mesh made as coarse as its data (issue 27). The lattice's cube is one size, the
// least h_i's, so where a cloud's spacing varies (the locally refined cylinder: 60:1) the
// sparse parts get triangles far smaller than their samples' spacing (that cylinder's 8,285
// points made 1.7 M triangles); and marching tetrahedra leaves slivers wherever the surface
// passes near a corner. Edges shorter than their vertices' share of the local cell collapse,
// one vertex into the other (a half-edge collapse: every vertex left is one the marching
// placed on the surface, with its normal), shortest first, while
// - the topology stays (the link condition of Dey et al. 1999: the two ends share no
//   neighbour but the edge's opposite corners; a boundary vertex moves only along its
//   boundary, the new boundary edge within the tolerance below of every boundary vertex it
//   stands for; no tetrahedron folds flat), so a watertight manifold stays one;
// - the triangles keep to the surface: the planes the removed vertices' triangles had stay
//   within a share of the cell of the vertex that takes them (Garland & Heckbert's quadrics,
//   1997, as a root mean square), so creases and curvature stop the coarsening, flat parts
//   do not;
// - no triangle turns more than 60°, and none falls below a quality of 0.15 unless one it
//   replaces already was (then not below that one).
#pragma once

#include <cstdint>
#include <span>

#include "pss/mesh/marching_tetrahedra.hpp"
#include "pss/mesh/triangle_mesh.hpp"

namespace pss {

// An edge shorter than this share of the cell at its ends collapses: marching's triangles
// have edges from about this share of the cube to √2 of it.
inline constexpr float kShortEdgeShare = 0.5f;
// The planes a vertex takes stay within this share of the cell of it (root mean square).
inline constexpr float kCoarseningError = 0.02f;

// Coarsens `mesh` as above, `cell[v]` the cube's side that suits vertex v (the local
// spacing's); removes the vertices it collapsed, keeping the others' order, and turns the
// normals that the turned triangles left facing against them (normals_follow_winding).
// On all cores, block by block, and the same for any thread count. Counts the vertices
// removed in counts.collapsed_vertices and adds the normals turned to counts.normals_turned.
// Throws Error unless there is one positive cell per vertex and every position is finite.
void coarsen_mesh(TriangleMesh& mesh, std::span<const float> cell, MarchCounts& counts);

}  // namespace pss
