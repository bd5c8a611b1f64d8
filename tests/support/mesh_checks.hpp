// What the mesh tests check of a closed surface, in one place.
#pragma once

#include <gtest/gtest.h>

#include <array>
#include <cmath>

#include <glm/ext/vector_double3.hpp>
#include <glm/geometric.hpp>

#include "pss/mesh/triangle_mesh.hpp"

namespace pss::test {

// One watertight component with Euler characteristic `euler` (2: a sphere's, 0: a torus's).
inline void expect_one_closed_surface(const TriangleMesh& mesh, std::int64_t euler) {
  const MeshTopology t = topology(mesh);
  EXPECT_TRUE(t.watertight());
  EXPECT_EQ(t.components, 1);
  EXPECT_EQ(t.euler_characteristic(), euler);
}

// A triangle's shape: 4√3·area / Σ edge², 1 when equilateral, 0 when flat.
inline double triangle_quality(const TriangleMesh& m, const std::array<int, 3>& t) {
  const glm::dvec3 a(m.positions[std::size_t(t[0])]), b(m.positions[std::size_t(t[1])]),
      c(m.positions[std::size_t(t[2])]);
  const double edges = glm::dot(b - a, b - a) + glm::dot(c - b, c - b) + glm::dot(a - c, a - c);
  return 2.0 * std::sqrt(3.0) * glm::length(glm::cross(b - a, c - a)) / edges;
}

}  // namespace pss::test
