// What the mesh tests check of a closed surface, in one place.
#pragma once

#include <gtest/gtest.h>

#include "pss/mesh/triangle_mesh.hpp"

namespace pss::test {

// One watertight component with Euler characteristic `euler` (2: a sphere's, 0: a torus's).
inline void expect_one_closed_surface(const TriangleMesh& mesh, std::int64_t euler) {
  const MeshTopology t = topology(mesh);
  EXPECT_TRUE(t.watertight());
  EXPECT_EQ(t.components, 1);
  EXPECT_EQ(t.euler_characteristic(), euler);
}

}  // namespace pss::test
