// MeshWelder (include/pss/mesh/weld.hpp): pieces of a march joined by their vertices' keys.
// Two pieces that share an edge's root share one vertex; the vertices come in the march's
// order (edges' roots by key, then crease fans' centres by cube) whatever order the pieces
// came in; a cube's triangles given twice are refused.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "pss/core/error.hpp"
#include "pss/mesh/weld.hpp"

namespace pss {
namespace {

// An edge's root's key (its lower corner's key << 3 | direction 1..7) and a fan centre's.
constexpr std::uint64_t edge(std::uint64_t corner, std::uint64_t direction) { return corner << 3 | direction; }
constexpr std::uint64_t centre(std::uint64_t cube) { return cube << 3; }

// A piece of one triangle per cube, each vertex at (key, 0, 0) so that its key shows.
MarchedPiece piece(const std::vector<std::uint64_t>& cubes, const std::vector<std::vector<std::uint64_t>>& keys) {
  MarchedPiece p;
  for (std::size_t t = 0; t < cubes.size(); ++t) {
    std::array<int, 3> triangle{};
    for (std::size_t k = 0; k < 3; ++k) {
      triangle[k] = int(p.vertex_key.size());
      p.vertex_key.push_back(keys[t][k]);
      p.mesh.positions.push_back(vec3(float(keys[t][k]), float(t), 0.0f));
      p.mesh.normals.push_back(vec3(0, 0, 1));
    }
    p.mesh.triangles.push_back(triangle);
    p.triangle_cube.push_back(cubes[t]);
    p.triangle_place.push_back(0);
  }
  return p;
}

std::vector<float> cells(const MarchedPiece& p) { return std::vector<float>(p.vertex_key.size(), 1.0f); }

TEST(MeshWelder, SharedKeysAreOneVertexInTheMarchsOrder) {
  // Cube 7's fan centre and two edges' roots; cube 3's triangle shares two roots with it.
  const MarchedPiece a = piece({7}, {{edge(9, 1), centre(7), edge(4, 2)}});
  const MarchedPiece b = piece({3}, {{edge(4, 2), edge(2, 5), edge(9, 1)}});
  MeshWelder welder;
  welder.add(a, cells(a));
  welder.add(b, cells(b));
  std::vector<float> cell;
  MarchCounts counts;
  const TriangleMesh mesh = welder.weld(cell, counts);
  ASSERT_EQ(mesh.positions.size(), 4u) << "a root two pieces share is one vertex";
  const std::vector<std::uint64_t> order{edge(2, 5), edge(4, 2), edge(9, 1), centre(7)};
  for (std::size_t v = 0; v < order.size(); ++v) EXPECT_EQ(mesh.positions[v].x, float(order[v])) << v;
  ASSERT_EQ(mesh.triangles.size(), 2u);
  // Cube 3's triangle first, each corner the vertex of its key.
  EXPECT_EQ(mesh.triangles[0], (std::array<int, 3>{1, 0, 2}));
  EXPECT_EQ(mesh.triangles[1], (std::array<int, 3>{2, 3, 1}));
  EXPECT_EQ(counts.crease_vertices, 1);
  EXPECT_EQ(cell.size(), 4u);
}

TEST(MeshWelder, ACubesTrianglesFromTwoPiecesAreRefused) {
  const MarchedPiece a = piece({5}, {{edge(1, 1), edge(2, 1), edge(3, 1)}});
  MeshWelder welder;
  welder.add(a, cells(a));
  welder.add(a, cells(a));
  std::vector<float> cell;
  MarchCounts counts;
  EXPECT_THROW(welder.weld(cell, counts), Error);
}

TEST(MeshWelder, APieceThatDoesNotHoldTogetherIsRefused) {
  MarchedPiece a = piece({5}, {{edge(1, 1), edge(2, 1), edge(3, 1)}});
  MeshWelder welder;
  EXPECT_THROW(welder.add(a, std::vector<float>(2, 1.0f)), Error) << "a cell for each vertex";
  a.mesh.triangles[0][1] = 3;
  EXPECT_THROW(welder.add(a, cells(a)), Error) << "a triangle's vertex past the piece's";
}

}  // namespace
}  // namespace pss
