// Pieces of one march (march_piece: `pss mesh` tile by tile, issue 28), each the triangles
// of its own box of cubes, joined into one mesh by their vertices' keys: a vertex two pieces
// share (a root on an edge between their boxes, or a crease fan's centre) is one vertex, so
// the seams have no cracks and no duplicate vertices.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "pss/mesh/marching_tetrahedra.hpp"

// (In a namespace of their own: sorting them finds std::swap alone, not core/platform.hpp's.)
namespace pss::weld_records {
struct Vertex {
  std::uint64_t key;
  vec3 position, normal;
  float cell;
};
struct Triangle {
  std::uint64_t cube;
  std::int32_t place;
  std::array<std::uint64_t, 3> keys;
};
}  // namespace pss::weld_records

namespace pss {

class MeshWelder {
 public:
  // A piece's triangles and vertices, and each vertex's value in `cell` (its cell for the
  // coarsening).
  void add(const MarchedPiece& piece, std::span<const float> cell);
  std::size_t triangles() const { return triangles_.size(); }

  // The mesh: each key's vertex once (the edges' roots in their keys' order, then the fans'
  // centres in their cubes'), the triangles in their cubes' order; then, as march_tetrahedra
  // does, the pinches removed and the normals turned to follow the winding (counted in
  // `counts`, with the fans' centres). `cell` gets each vertex's value. Throws Error where two pieces gave one cube's
  // triangles, or a triangle names a vertex no piece gave.
  TriangleMesh weld(std::vector<float>& cell, MarchCounts& counts);

 private:
  using Vertex = weld_records::Vertex;
  using Triangle = weld_records::Triangle;
  std::vector<Vertex> vertices_;
  std::vector<Triangle> triangles_;
};

}  // namespace pss
