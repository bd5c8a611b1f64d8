#include <algorithm>

#include <glm/ext/vector_double3.hpp>
#include <glm/geometric.hpp>

#include "incidence.hpp"
#include "pss/mesh/triangle_mesh.hpp"

namespace pss {

namespace {

// A component with at most one boundary edge in this many is nearly closed: a few small
// holes, whose lids change its volume little.
constexpr std::int64_t kNearlyClosed = 100;

}  // namespace

namespace mesh_detail {

Incidence incidence(const std::vector<std::array<int, 3>>& triangles) {
  const std::size_t nt = triangles.size();
  Incidence in{{}, ConnectedComponents<std::int64_t>(nt), ConnectedComponents<std::int64_t>(3 * nt)};
  // The sides sorted on (low, high, triangle) in about linear time: counted into one bucket
  // per lower vertex, then each bucket, a vertex's few edges, sorted on its own.
  int vertices = 0;
  for (const auto& t : triangles) vertices = std::max({vertices, t[0] + 1, t[1] + 1, t[2] + 1});
  std::vector<std::int64_t> start(std::size_t(vertices) + 1, 0);
  auto side = [&](std::size_t i, int k) {
    const int a = triangles[i][std::size_t(k)], b = triangles[i][std::size_t((k + 1) % 3)];
    return Side{std::min(a, b), std::max(a, b), a < b, std::int64_t(i)};
  };
  for (std::size_t i = 0; i < nt; ++i)
    for (int k = 0; k < 3; ++k) ++start[std::size_t(side(i, k).low) + 1];
  for (std::size_t v = 0; v < std::size_t(vertices); ++v) start[v + 1] += start[v];
  in.sides.resize(3 * nt);
  std::vector<std::int64_t> next(start.begin(), start.end() - 1);
  for (std::size_t i = 0; i < nt; ++i)
    for (int k = 0; k < 3; ++k) {
      const Side s = side(i, k);
      in.sides[std::size_t(next[std::size_t(s.low)]++)] = s;
    }
  for (std::size_t v = 0; v < std::size_t(vertices); ++v)
    std::sort(in.sides.begin() + start[v], in.sides.begin() + start[v + 1], [](const Side& x, const Side& y) {
      return x.high != y.high ? x.high < y.high : x.triangle < y.triangle;
    });
  auto corner = [&](std::int64_t triangle, int vertex) -> std::int64_t {
    const auto& v = triangles[std::size_t(triangle)];
    return 3 * triangle + (v[0] == vertex ? 0 : v[1] == vertex ? 1 : 2);
  };
  for (std::size_t i = 0; i < in.sides.size();) {
    std::size_t j = i + 1;
    while (j < in.sides.size() && in.sides[j].same_edge(in.sides[i])) ++j;
    const Side& first = in.sides[i];
    for (std::size_t k = i + 1; k < j; ++k) {
      const Side& other = in.sides[k];
      in.components.join(first.triangle, other.triangle);
      if (first.low == first.high || other.low == other.high) continue;
      in.fans.join(corner(first.triangle, first.low), corner(other.triangle, other.low));
      in.fans.join(corner(first.triangle, first.high), corner(other.triangle, other.high));
    }
    i = j;
  }
  return in;
}

}  // namespace mesh_detail

MeshTopology topology(const TriangleMesh& mesh) {
  MeshTopology t;
  const std::size_t nv = mesh.positions.size(), nt = mesh.triangles.size();
  t.vertices = std::int64_t(nv);
  t.triangles = std::int64_t(nt);
  std::vector<char> used(nv, 0);
  for (const auto& v : mesh.triangles) {
    if (v[0] == v[1] || v[1] == v[2] || v[2] == v[0]) ++t.degenerate_triangles;
    for (int k : v) used[std::size_t(k)] = 1;
  }
  t.unreferenced_vertices = std::int64_t(std::count(used.begin(), used.end(), 0));

  mesh_detail::Incidence in = mesh_detail::incidence(mesh.triangles);
  const auto& sides = in.sides;
  for (std::size_t i = 0; i < sides.size();) {
    std::size_t j = i + 1;
    while (j < sides.size() && sides[j].same_edge(sides[i])) ++j;
    ++t.edges;
    const std::size_t count = j - i;
    if (count == 1) ++t.boundary_edges;
    if (count >= 3) ++t.non_manifold_edges;
    if (count == 2 && sides[i].forward == sides[i + 1].forward) ++t.misoriented_edges;
    i = j;
  }
  for (std::size_t i = 0; i < nt; ++i) t.components += in.components.find(std::int64_t(i)) == std::int64_t(i);

  std::vector<std::int64_t> fan_of(nv, -1);
  std::vector<char> counted(nv, 0);
  for (std::size_t i = 0; i < nt; ++i)
    for (std::size_t k = 0; k < 3; ++k) {
      const auto vertex = std::size_t(mesh.triangles[i][k]);
      const std::int64_t fan = in.fans.find(std::int64_t(3 * i + k));
      if (fan_of[vertex] < 0) {
        fan_of[vertex] = fan;
      } else if (fan_of[vertex] != fan && !counted[vertex]) {
        counted[vertex] = 1;
        ++t.non_manifold_vertices;
      }
    }
  return t;
}

double enclosed_volume(const TriangleMesh& mesh) {
  mesh_detail::Incidence in = mesh_detail::incidence(mesh.triangles);
  const std::size_t nt = mesh.triangles.size();
  if (nt == 0) return 0;
  // Edges and boundary edges by component (its root triangle).
  std::vector<std::int64_t> edges(nt, 0), boundary(nt, 0);
  const auto& sides = in.sides;
  for (std::size_t i = 0; i < sides.size();) {
    std::size_t j = i + 1;
    while (j < sides.size() && sides[j].same_edge(sides[i])) ++j;
    const auto root = std::size_t(in.components.find(sides[i].triangle));
    ++edges[root];
    boundary[root] += j - i == 1;
    i = j;
  }
  // Σ det(a − o, b − o, c − o)/6 about one vertex o of each component, in double: the
  // divergence theorem, exact for a closed surface; a hole's lid, left out, is small where
  // the holes are.
  std::vector<glm::dvec3> origin(nt);
  std::vector<char> has_origin(nt, 0);
  double volume = 0;
  for (std::size_t t = 0; t < nt; ++t) {
    const auto root = std::size_t(in.components.find(std::int64_t(t)));
    if (boundary[root] * kNearlyClosed > edges[root]) continue;
    const auto& v = mesh.triangles[t];
    if (!has_origin[root]) {
      origin[root] = glm::dvec3(mesh.positions[std::size_t(v[0])]);
      has_origin[root] = 1;
    }
    const glm::dvec3 o = origin[root], a = glm::dvec3(mesh.positions[std::size_t(v[0])]) - o,
                     b = glm::dvec3(mesh.positions[std::size_t(v[1])]) - o,
                     c = glm::dvec3(mesh.positions[std::size_t(v[2])]) - o;
    volume += glm::dot(a, glm::cross(b, c)) / 6;
  }
  return volume;
}

void turn_inside_out(TriangleMesh& mesh) {
  for (auto& t : mesh.triangles) std::swap(t[1], t[2]);
  for (vec3& n : mesh.normals) n = -n;
}

}  // namespace pss
