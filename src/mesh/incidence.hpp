// How a mesh's triangles meet (internal to src/mesh): its edges with the triangles on each,
// the components triangles make across edges, and the fans a vertex's corners make across
// the edges at it. What topology() counts and remove_pinches() repairs.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "pss/core/connected_components.hpp"
#include "pss/mesh/triangle_mesh.hpp"

namespace pss::mesh_detail {

// One side of a triangle, the edge between `low` < `high`; `forward` when the triangle
// runs from low to high.
struct Side {
  int low, high;
  int triangle;  // 16 bytes a side, not 24: a mesh has three sides a triangle (issue 28)
  bool forward;
  bool same_edge(const Side& o) const { return low == o.low && high == o.high; }
};

struct Incidence {
  std::vector<Side> sides;  // sorted by edge, then triangle: an edge's sides are a run
  ConnectedComponents<std::int64_t> components;  // of triangles
  ConnectedComponents<std::int64_t> fans;        // of corners 3·triangle + k (vertex k of the triangle)
};

// Triangles with a repeated vertex take part in no fan (their corners stay alone). Throws
// Error for 2^31 triangles or more (march_tetrahedra makes fewer).
Incidence incidence(const std::vector<std::array<int, 3>>& triangles);

// Per component, indexed by its root triangle (in.components): its area, whether it counts
// closed (its holes' lids, fans from each hole's centre, at most a quarter of its area), and
// then the volume its triangles and lids enclose, signed by their winding (else 0).
struct ComponentVolumes {
  std::vector<double> volume, area;
  std::vector<char> closed;
};
ComponentVolumes component_volumes(const TriangleMesh& mesh, Incidence& in);
// What enclosed_volume (triangle_mesh.hpp) gives, from the components' volumes.
double enclosed_volume(const ComponentVolumes& parts, double* closed_share);
// face_closed_parts_outward (triangle_mesh.hpp) of the mesh whose incidence and volumes
// these are (the winding may have been turned since, the volumes negated with it).
std::int64_t face_closed_parts_outward(TriangleMesh& mesh, Incidence& in, const ComponentVolumes& volumes);

}  // namespace pss::mesh_detail
