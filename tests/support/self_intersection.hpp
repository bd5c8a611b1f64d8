// Whether a mesh's triangles cross each other, found independently of the mesher: every pair
// of triangles with no vertex in common whose boxes overlap (a uniform grid of buckets)
// is tested edge against triangle, both ways, with orientation predicates in double, and
// vertex against triangle: within 10⁻⁶ of the mesh's box diagonal counts as touching.
#pragma once

#include <cstdint>

#include "pss/mesh/triangle_mesh.hpp"

namespace pss::test {

// The number of pairs of triangles that cross or touch (share no vertex, and an edge of one
// pierces the other or a vertex of one lies on the other).
std::int64_t crossing_triangle_pairs(const TriangleMesh& mesh);

}  // namespace pss::test
