#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include <glm/ext/vector_double3.hpp>
#include <glm/geometric.hpp>

#include "incidence.hpp"
#include "pss/mesh/triangle_mesh.hpp"

namespace pss {

namespace {

struct ClosedPart {
  std::vector<std::size_t> triangles;
  glm::dvec3 lo{std::numeric_limits<double>::infinity()}, hi{-std::numeric_limits<double>::infinity()};
  double volume = 0;  // signed: positive where its triangles face out
};

// Whether the ray from p along d crosses triangle (a, b, c) (Möller–Trumbore, in double).
bool crosses(glm::dvec3 p, glm::dvec3 d, glm::dvec3 a, glm::dvec3 b, glm::dvec3 c) {
  const glm::dvec3 e1 = b - a, e2 = c - a, q = glm::cross(d, e2);
  const double det = glm::dot(e1, q);
  if (det == 0) return false;
  const glm::dvec3 s = p - a;
  const double u = glm::dot(s, q) / det;
  if (u < 0 || u > 1) return false;
  const glm::dvec3 r = glm::cross(s, e1);
  const double v = glm::dot(d, r) / det;
  return v >= 0 && u + v <= 1 && glm::dot(e2, r) / det > 0;
}

}  // namespace

namespace mesh_detail {

std::int64_t face_closed_parts_outward(TriangleMesh& mesh, Incidence& in, const ComponentVolumes& volumes) {
  const std::size_t nt = mesh.triangles.size();
  auto position = [&](int v) { return glm::dvec3(mesh.positions[std::size_t(v)]); };
  // The closed components, those nearly closed by their holes' lids too (enclosed_volume).
  std::vector<int> part_of(nt, -1);
  std::vector<ClosedPart> parts;
  for (std::size_t t = 0; t < nt; ++t) {
    const auto root = std::size_t(in.components.find(std::int64_t(t)));
    if (!volumes.closed[root]) continue;
    if (part_of[root] < 0) {
      part_of[root] = int(parts.size());
      parts.emplace_back();
      parts.back().volume = volumes.volume[root];
    }
    ClosedPart& part = parts[std::size_t(part_of[root])];
    part.triangles.push_back(t);
    for (const int k : mesh.triangles[t]) {
      part.lo = glm::min(part.lo, position(k));
      part.hi = glm::max(part.hi, position(k));
    }
  }
  // Each part's depth: how many others hold its first vertex (a ray's crossings, odd inside;
  // a nearly closed part's holes are not counted). A part at an even depth faces out, one at
  // an odd depth (a cavity's wall) in.
  const glm::dvec3 ray = glm::normalize(glm::dvec3(0.5773, 0.5779, 0.5767));  // along no lattice plane
  std::int64_t turned = 0;
  std::vector<char> turn(parts.size(), 0);
  for (std::size_t c = 0; c < parts.size(); ++c) {
    const glm::dvec3 p = position(mesh.triangles[parts[c].triangles.front()][0]);
    int depth = 0;
    for (std::size_t e = 0; e < parts.size(); ++e) {
      if (e == c || glm::any(glm::lessThan(p, parts[e].lo)) || glm::any(glm::greaterThan(p, parts[e].hi))) continue;
      int crossings = 0;
      for (const std::size_t t : parts[e].triangles) {
        const auto& v = mesh.triangles[t];
        crossings += crosses(p, ray, position(v[0]), position(v[1]), position(v[2]));
      }
      depth += crossings % 2;
    }
    turn[c] = (parts[c].volume < 0) == (depth % 2 == 0);
  }
  std::vector<char> flip_vertex(mesh.positions.size(), 0);
  for (std::size_t c = 0; c < parts.size(); ++c) {
    if (!turn[c]) continue;
    ++turned;
    for (const std::size_t t : parts[c].triangles) {
      auto& v = mesh.triangles[t];
      std::swap(v[1], v[2]);
      for (const int k : v) flip_vertex[std::size_t(k)] = 1;
    }
  }
  for (std::size_t v = 0; v < mesh.normals.size(); ++v)
    if (flip_vertex[v]) mesh.normals[v] = -mesh.normals[v];
  return turned;
}

}  // namespace mesh_detail

std::int64_t face_closed_parts_outward(TriangleMesh& mesh) {
  if (mesh.triangles.empty()) return 0;
  mesh_detail::Incidence in = mesh_detail::incidence(mesh.triangles);
  return mesh_detail::face_closed_parts_outward(mesh, in, mesh_detail::component_volumes(mesh, in));
}

}  // namespace pss
