// A triangle mesh on the host (what `pss mesh` makes, mesh/mesh_cloud.hpp), and what its
// topology is: the checks a user of a mesh relies on (issue 27), computed, not assumed.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <glm/ext/vector_double3.hpp>

#include "pss/core/types.hpp"

namespace pss {

struct TriangleMesh {
  glm::dvec3 origin{0.0};        // world positions are origin + positions[i] (as PointCloud's)
  std::vector<vec3> positions;   // from origin
  std::vector<vec3> normals;     // unit, one per position: the surface's, not the faces'
  std::vector<std::array<int, 3>> triangles;  // counter-clockwise seen from outside
};

struct MeshTopology {
  std::int64_t vertices = 0, edges = 0, triangles = 0;
  std::int64_t boundary_edges = 0;           // in one triangle
  std::int64_t non_manifold_edges = 0;       // in three or more
  std::int64_t non_manifold_vertices = 0;    // whose triangles are not one fan
  std::int64_t misoriented_edges = 0;        // two triangles crossing it the same way
  std::int64_t degenerate_triangles = 0;     // a vertex twice
  std::int64_t unreferenced_vertices = 0;
  std::int64_t components = 0;               // joined by shared edges
  std::int64_t euler_characteristic() const { return vertices - edges + triangles; }
  bool manifold() const {
    return non_manifold_edges == 0 && non_manifold_vertices == 0 && misoriented_edges == 0 &&
           degenerate_triangles == 0;
  }
  bool watertight() const { return manifold() && boundary_edges == 0; }
};

MeshTopology topology(const TriangleMesh& mesh);

// The volume the mesh's closed components enclose, signed: positive where their triangles
// face outward (counter-clockwise seen from outside), negative where inward. A cavity's
// closed surface, facing into the cavity, counts negative, as it should. Components nearly
// closed (their holes' lids, fans from each hole's centre, at most a quarter of their area)
// count closed by those lids; others, a sheet or a scan of one side, enclose nothing and
// count 0. closed_share, where given, gets the share of the mesh's area in the components
// counted closed.
double enclosed_volume(const TriangleMesh& mesh, double* closed_share = nullptr);

// Removes the vertices no triangle uses, keeping the others' order, and their values in
// `follow` (one a vertex), where given.
void drop_unused_vertices(TriangleMesh& mesh, std::vector<float>* follow = nullptr);

// Every triangle's winding reversed and every normal negated.
void turn_inside_out(TriangleMesh& mesh);

// Turns each closed component (as enclosed_volume counts them: nearly closed ones by their
// holes' lids) that faces the wrong way for its depth: one inside no other (or inside an even number) must enclose a positive volume, one
// inside an odd number, a cavity's wall, a negative one; depth by the parity of a ray's
// crossings. Where the side was a guess, parts the orientation joined across a gap may
// come out one in, one out. Returns how many it turned.
std::int64_t face_closed_parts_outward(TriangleMesh& mesh);

// Turns each vertex normal that faces against its triangles (the sum of their area vectors,
// which their winding points outward), so that shading with the normals sees the faces'
// outside. Returns how many it turned.
std::int64_t normals_follow_winding(TriangleMesh& mesh);

}  // namespace pss
