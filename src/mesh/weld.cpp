#include "pss/mesh/weld.hpp"

#include <algorithm>

#include "pss/core/error.hpp"
#include "pss/core/memory.hpp"

namespace pss {

void MeshWelder::add(const MarchedPiece& piece, std::span<const float> cell) {
  const TriangleMesh& mesh = piece.mesh;
  if (cell.size() != mesh.positions.size() || piece.vertex_key.size() != mesh.positions.size() ||
      piece.triangle_cube.size() != mesh.triangles.size() || piece.triangle_place.size() != mesh.triangles.size())
    throw Error("a piece of the mesh does not hold together");
  for (std::size_t v = 0; v < mesh.positions.size(); ++v)
    vertices_.push_back({piece.vertex_key[v], mesh.positions[v], mesh.normals[v], cell[v]});
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    Triangle triangle{piece.triangle_cube[t], piece.triangle_place[t], {}};
    for (std::size_t k = 0; k < 3; ++k) {
      const auto v = std::size_t(mesh.triangles[t][k]);
      if (v >= piece.vertex_key.size()) throw Error("a piece of the mesh does not hold together");
      triangle.keys[k] = piece.vertex_key[v];
    }
    triangles_.push_back(triangle);
  }
}

TriangleMesh MeshWelder::weld(std::vector<float>& cell, MarchCounts& counts) {
  // A fan's centre (key's direction 0) after every edge's root, as march_tetrahedra puts them.
  const auto order = [](std::uint64_t a, std::uint64_t b) {
    const bool ca = (a & 7) == 0, cb = (b & 7) == 0;
    return ca != cb ? cb : a < b;
  };
  std::stable_sort(vertices_.begin(), vertices_.end(),
                   [&](const Vertex& a, const Vertex& b) { return order(a.key, b.key); });
  vertices_.erase(std::unique(vertices_.begin(), vertices_.end(),
                              [](const Vertex& a, const Vertex& b) { return a.key == b.key; }),
                  vertices_.end());
  counts.crease_vertices =
      std::count_if(vertices_.begin(), vertices_.end(), [](const Vertex& v) { return (v.key & 7) == 0; });
  std::sort(triangles_.begin(), triangles_.end(), [](const Triangle& a, const Triangle& b) {
    return a.cube != b.cube ? a.cube < b.cube : a.place < b.place;
  });
  for (std::size_t t = 1; t < triangles_.size(); ++t)
    if (triangles_[t].cube == triangles_[t - 1].cube && triangles_[t].place == triangles_[t - 1].place)
      throw Error("two pieces of the mesh gave one cube's triangles");
  if (vertices_.size() > std::size_t(INT32_MAX) || triangles_.size() > std::size_t(INT32_MAX))
    throw Error("the mesh would have more than 2^31 vertices or triangles: use a larger cell");

  TriangleMesh mesh;
  mesh.positions.resize(vertices_.size());
  mesh.normals.resize(vertices_.size());
  cell.resize(vertices_.size());
  std::vector<std::uint64_t> keys(vertices_.size());
  for (std::size_t v = 0; v < vertices_.size(); ++v) {
    mesh.positions[v] = vertices_[v].position;
    mesh.normals[v] = vertices_[v].normal;
    cell[v] = vertices_[v].cell;
    keys[v] = vertices_[v].key;
  }
  release(vertices_);
  mesh.triangles.resize(triangles_.size());
  for (std::size_t t = 0; t < triangles_.size(); ++t)
    for (std::size_t k = 0; k < 3; ++k) {
      const auto at = std::lower_bound(keys.begin(), keys.end(), triangles_[t].keys[k], order);
      if (at == keys.end() || *at != triangles_[t].keys[k]) throw Error("a piece of the mesh names a vertex none gave");
      mesh.triangles[t][k] = int(at - keys.begin());
    }
  release(triangles_);
  counts.pinched_triangles += remove_pinches(mesh, &cell);
  counts.normals_turned += normals_follow_winding(mesh);
  return mesh;
}

}  // namespace pss
