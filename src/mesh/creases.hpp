// Sharp creases in a marched mesh (issue 27; internal to src/mesh). Marching puts every
// vertex on a cube's edge, so a crease that crosses a cube is cut off by a chamfer as wide as
// the cube. Where the normals of a cube's patch differ by more than the crease angle, the
// patch is replaced by a fan around the point that fits its vertices' tangent planes best
// (the quadratic error function of dual contouring, Ju et al. 2002, in the fans of Kobbelt et
// al.'s extended marching cubes, 2001), if that point lies inside the cube and on the
// surface; then the edges between two such fans are flipped to join their centres, so that
// the crease runs along them.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "pss/mesh/implicit.hpp"
#include "pss/mesh/triangle_mesh.hpp"

namespace pss::mesh_detail {

// The marched cubes' triangles: cube i's are mesh.triangles[first[i], first[i + 1]) and its
// lowest corner is lowest[i]. snap_creases keeps `first` so, and lists the cube of each fan
// centre it adds in `centres`.
struct CubeTriangles {
  std::vector<vec3> lowest;
  std::vector<std::size_t> first;  // one more than the cubes
  std::vector<std::size_t> centres;
};

struct CreaseCounts {
  std::int64_t vertices = 0;  // fans' centres placed on creases
  std::int64_t flips = 0;     // edges flipped to join two of them
};

// A fan's centre lies on the surface when the implicit there is within this share of the
// cube's side of zero: it is then as near as the edges' roots (their tolerance, kRootTolerance,
// with the error of the normals' fit), and a rounded edge, whose tangent planes meet off it,
// keeps its chamfer.
inline constexpr float kCreaseOnSurface = 0.02f;

// Replaces the patch of each cube whose vertices' normals differ by more than
// `crease_angle` degrees (180: none) by a fan as above, where the patch is one disk, its
// fan's centre lies inside the cube, on the surface (implicit.sample) and makes no triangle
// face against its edge's normals. The mesh keeps its boundary edges, so it stays watertight
// where it was; a fan from a point inside a convex cube over a loop on its faces is
// embedded, so no triangle crosses another. Vertices no triangle uses are left (for
// remove_pinches to drop). The flips keep each triangle in its cube's range.
CreaseCounts snap_creases(TriangleMesh& mesh, CubeTriangles& cubes, float cell, const ImplicitSurface& implicit,
                          float crease_angle);

}  // namespace pss::mesh_detail
