#include <algorithm>
#include <limits>

#include <glm/ext/vector_double3.hpp>
#include <glm/geometric.hpp>

#include "incidence.hpp"
#include "pss/backend/cpu/parallel_for.hpp"
#include "pss/core/error.hpp"
#include "pss/mesh/triangle_mesh.hpp"

namespace pss {

namespace {

// A component whose holes' lids have at most this share of its area is nearly closed: the
// lids close it. A wider opening is a sheet's or a scan of one side's (a hemisphere's lid
// is half its area), which encloses nothing.
constexpr double kLidShare = 0.25;

}  // namespace

namespace mesh_detail {

Incidence incidence(const std::vector<std::array<int, 3>>& triangles) {
  const std::size_t nt = triangles.size();
  if (nt > std::size_t(std::numeric_limits<int>::max())) throw Error("a mesh of 2^31 triangles or more");
  Incidence in{{}, ConnectedComponents<std::int64_t>(nt), ConnectedComponents<std::int64_t>(3 * nt)};
  // The sides sorted on (low, high, triangle) in about linear time: counted into one bucket
  // per lower vertex, then each bucket, a vertex's few edges, sorted on its own.
  int vertices = 0;
  for (const auto& t : triangles) vertices = std::max({vertices, t[0] + 1, t[1] + 1, t[2] + 1});
  std::vector<std::int64_t> start(std::size_t(vertices) + 1, 0);
  auto side = [&](std::size_t i, int k) {
    const int a = triangles[i][std::size_t(k)], b = triangles[i][std::size_t((k + 1) % 3)];
    return Side{std::min(a, b), std::max(a, b), int(i), a < b};
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
  cpu::parallel_for(std::int64_t(vertices), [&](std::int64_t v) {
    std::sort(in.sides.begin() + start[std::size_t(v)], in.sides.begin() + start[std::size_t(v) + 1],
              [](const Side& x, const Side& y) { return x.high != y.high ? x.high < y.high : x.triangle < y.triangle; });
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

namespace mesh_detail {

ComponentVolumes component_volumes(const TriangleMesh& mesh, Incidence& in) {
  const std::size_t nt = mesh.triangles.size(), nv = mesh.positions.size();
  ComponentVolumes out{std::vector<double>(nt, 0.0), std::vector<double>(nt, 0.0), std::vector<char>(nt, 0)};
  auto position = [&](int v) { return glm::dvec3(mesh.positions[std::size_t(v)]); };
  // The rim: each edge with one side, as its triangle runs, and the component it bounds
  // (its root triangle); its holes: the rim's pieces joined at their vertices.
  struct RimEdge {
    int from, to;
    std::size_t component;
  };
  std::vector<RimEdge> rim;
  ConnectedComponents<std::int64_t> holes(nv);
  const auto& sides = in.sides;
  for (std::size_t i = 0; i < sides.size();) {
    std::size_t j = i + 1;
    while (j < sides.size() && sides[j].same_edge(sides[i])) ++j;
    const mesh_detail::Side& s = sides[i];
    if (j - i == 1 && s.low != s.high) {
      rim.push_back({s.forward ? s.low : s.high, s.forward ? s.high : s.low,
                     std::size_t(in.components.find(s.triangle))});
      holes.join(s.low, s.high);
    }
    i = j;
  }
  // Each hole's centre (the mean of its edges' ends) and its vector area ½ Σ a × b (its
  // lid's area where flat); each component's own area and its holes'.
  std::vector<glm::dvec3> centre(nv, glm::dvec3(0.0)), hole_area(nv, glm::dvec3(0.0));
  std::vector<double> ends(nv, 0), lids(nt, 0);
  std::vector<double>& area = out.area;
  for (const RimEdge& e : rim) {
    const auto hole = std::size_t(holes.find(e.from));
    centre[hole] += position(e.from) + position(e.to);
    ends[hole] += 2;
    hole_area[hole] += glm::cross(position(e.from), position(e.to)) / 2.0;
  }
  for (const RimEdge& e : rim) {
    const auto hole = std::size_t(holes.find(e.from));
    if (ends[hole] == 0) continue;  // counted
    centre[hole] /= ends[hole];
    lids[e.component] += glm::length(hole_area[hole]);
    ends[hole] = 0;
  }
  for (std::size_t t = 0; t < nt; ++t) {
    const auto& v = mesh.triangles[t];
    area[std::size_t(in.components.find(std::int64_t(t)))] +=
        glm::length(glm::cross(position(v[1]) - position(v[0]), position(v[2]) - position(v[0]))) / 2;
  }
  // Σ det(a − o, b − o, c − o)/6 over the triangles and the holes' lids (fans from their
  // centres, run against the rim) of each nearly closed component, about a vertex o of its
  // root (least) triangle, in double: the divergence theorem, exact for a closed surface.
  auto cone = [&](glm::dvec3 a, glm::dvec3 b, glm::dvec3 c, std::size_t component) {
    const glm::dvec3 o = position(mesh.triangles[component][0]);
    return glm::dot(a - o, glm::cross(b - o, c - o)) / 6;
  };
  for (std::size_t c = 0; c < nt; ++c) out.closed[c] = area[c] > 0 && lids[c] <= kLidShare * area[c];
  for (std::size_t t = 0; t < nt; ++t) {
    const auto component = std::size_t(in.components.find(std::int64_t(t)));
    const auto& v = mesh.triangles[t];
    if (out.closed[component]) out.volume[component] += cone(position(v[0]), position(v[1]), position(v[2]), component);
  }
  for (const RimEdge& e : rim)
    if (out.closed[e.component])
      out.volume[e.component] += cone(position(e.to), position(e.from), centre[std::size_t(holes.find(e.from))], e.component);
  return out;
}

double enclosed_volume(const ComponentVolumes& parts, double* closed_share) {
  double volume = 0, total = 0, in_closed = 0;
  for (std::size_t c = 0; c < parts.volume.size(); ++c) {
    volume += parts.volume[c];
    total += parts.area[c];
    if (parts.closed[c]) in_closed += parts.area[c];
  }
  if (closed_share) *closed_share = total > 0 ? in_closed / total : 0;
  return volume;
}

}  // namespace mesh_detail

double enclosed_volume(const TriangleMesh& mesh, double* closed_share) {
  if (closed_share) *closed_share = 0;
  if (mesh.triangles.empty()) return 0;
  mesh_detail::Incidence in = mesh_detail::incidence(mesh.triangles);
  return mesh_detail::enclosed_volume(mesh_detail::component_volumes(mesh, in), closed_share);
}

void drop_unused_vertices(TriangleMesh& mesh, std::vector<float>* follow) {
  std::vector<int> renumber(mesh.positions.size(), -1);
  for (const auto& t : mesh.triangles)
    for (int v : t) renumber[std::size_t(v)] = 0;
  int next = 0;
  for (std::size_t v = 0; v < renumber.size(); ++v)
    if (renumber[v] == 0) {
      renumber[v] = next;
      mesh.positions[std::size_t(next)] = mesh.positions[v];
      if (!mesh.normals.empty()) mesh.normals[std::size_t(next)] = mesh.normals[v];
      if (follow != nullptr) (*follow)[std::size_t(next)] = (*follow)[v];
      ++next;
    }
  mesh.positions.resize(std::size_t(next));
  if (follow != nullptr) follow->resize(std::size_t(next));
  if (!mesh.normals.empty()) mesh.normals.resize(std::size_t(next));
  for (auto& t : mesh.triangles)
    for (int& v : t) v = renumber[std::size_t(v)];
}

void turn_inside_out(TriangleMesh& mesh) {
  for (auto& t : mesh.triangles) std::swap(t[1], t[2]);
  for (vec3& n : mesh.normals) n = -n;
}

std::int64_t normals_follow_winding(TriangleMesh& mesh) {
  std::vector<glm::dvec3> faces(mesh.positions.size(), glm::dvec3(0.0));
  for (const auto& t : mesh.triangles) {
    const glm::dvec3 a(mesh.positions[std::size_t(t[0])]), b(mesh.positions[std::size_t(t[1])]),
        c(mesh.positions[std::size_t(t[2])]);
    const glm::dvec3 area = glm::cross(b - a, c - a);  // twice the area, outward
    for (const int v : t) faces[std::size_t(v)] += area;
  }
  std::int64_t turned = 0;
  for (std::size_t v = 0; v < mesh.normals.size(); ++v)
    if (glm::dot(faces[v], glm::dvec3(mesh.normals[v])) < 0) {
      mesh.normals[v] = -mesh.normals[v];
      ++turned;
    }
  return turned;
}

}  // namespace pss
