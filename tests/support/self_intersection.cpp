#include "support/self_intersection.hpp"

#include <algorithm>
#include <cmath>
#include <unordered_map>
#include <vector>

#include <glm/ext/vector_double3.hpp>
#include <glm/geometric.hpp>

namespace pss::test {

namespace {

using d3 = glm::dvec3;

// Triangles that share no vertex must not touch either: a vertex this close to another
// triangle (in the mesh's box diagonals; float positions are good to about 6·10⁻⁸ of it)
// counts as crossing it, as the common checkers (Open3D, MeshLab) count it.
constexpr double kTouching = 1e-6;

double orient(const d3& a, const d3& b, const d3& c, const d3& d) { return glm::dot(a - d, glm::cross(b - d, c - d)); }

// Whether the segment pq passes through the triangle abc's interior (strictly: touching
// at an edge or a vertex does not count).
bool pierces(const d3& p, const d3& q, const d3& a, const d3& b, const d3& c) {
  const double sp = orient(a, b, c, p), sq = orient(a, b, c, q);
  if (!(sp > 0 && sq < 0) && !(sp < 0 && sq > 0)) return false;
  const double u = orient(p, q, a, b), v = orient(p, q, b, c), w = orient(p, q, c, a);
  return (u > 0 && v > 0 && w > 0) || (u < 0 && v < 0 && w < 0);
}

// The distance from p to the triangle abc (Ericson, Real-Time Collision Detection, 5.1.5).
double distance_to_triangle(const d3& p, const d3& a, const d3& b, const d3& c) {
  const d3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) return glm::length(p - a);
  const d3 bp = p - b;
  const double d3_ = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
  if (d3_ >= 0 && d4 <= d3_) return glm::length(p - b);
  const double vc = d1 * d4 - d3_ * d2;
  if (vc <= 0 && d1 >= 0 && d3_ <= 0) return glm::length(p - (a + ab * (d1 / (d1 - d3_))));
  const d3 cp = p - c;
  const double d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return glm::length(p - c);
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return glm::length(p - (a + ac * (d2 / (d2 - d6))));
  const double va = d3_ * d6 - d5 * d4;
  if (va <= 0 && d4 - d3_ >= 0 && d5 - d6 >= 0)
    return glm::length(p - (b + (c - b) * ((d4 - d3_) / ((d4 - d3_) + (d5 - d6)))));
  const double denominator = 1 / (va + vb + vc);
  return glm::length(p - (a + ab * (vb * denominator) + ac * (vc * denominator)));
}

}  // namespace

std::int64_t crossing_triangle_pairs(const TriangleMesh& mesh) {
  const std::size_t nt = mesh.triangles.size();
  if (nt == 0) return 0;
  d3 box_lo(mesh.positions[0]), box_hi(mesh.positions[0]);
  for (const vec3& p : mesh.positions) {
    box_lo = glm::min(box_lo, d3(p));
    box_hi = glm::max(box_hi, d3(p));
  }
  const double touching = kTouching * glm::length(box_hi - box_lo);
  std::vector<d3> lo(nt), hi(nt);
  double mean_extent = 0;
  for (std::size_t t = 0; t < nt; ++t) {
    lo[t] = hi[t] = d3(mesh.positions[std::size_t(mesh.triangles[t][0])]);
    for (int v : mesh.triangles[t]) {
      lo[t] = glm::min(lo[t], d3(mesh.positions[std::size_t(v)]));
      hi[t] = glm::max(hi[t], d3(mesh.positions[std::size_t(v)]));
    }
    const d3 e = hi[t] - lo[t];
    mean_extent += std::max({e.x, e.y, e.z}) / double(nt);
  }
  // Buckets a few triangles wide: each triangle in every bucket its box touches.
  const double size = 2 * mean_extent + 1e-12;
  std::unordered_map<std::uint64_t, std::vector<int>> buckets;
  auto key = [](std::int64_t x, std::int64_t y, std::int64_t z) {
    return (std::uint64_t(x & 0x1fffff) << 42) | (std::uint64_t(y & 0x1fffff) << 21) | std::uint64_t(z & 0x1fffff);
  };
  for (std::size_t t = 0; t < nt; ++t) {
    const glm::i64vec3 a(glm::floor(lo[t] / size)), b(glm::floor(hi[t] / size));
    for (std::int64_t x = a.x; x <= b.x; ++x)
      for (std::int64_t y = a.y; y <= b.y; ++y)
        for (std::int64_t z = a.z; z <= b.z; ++z) buckets[key(x, y, z)].push_back(int(t));
  }
  std::vector<std::pair<int, int>> crossing;
  for (const auto& [k, list] : buckets)
    for (std::size_t i = 0; i < list.size(); ++i)
      for (std::size_t j = i + 1; j < list.size(); ++j) {
        const auto s = std::size_t(list[i]), t = std::size_t(list[j]);
        const auto& a = mesh.triangles[s];
        const auto& b = mesh.triangles[t];
        if (std::any_of(a.begin(), a.end(), [&](int v) { return std::find(b.begin(), b.end(), v) != b.end(); })) continue;
        if (glm::any(glm::lessThan(hi[s], lo[t])) || glm::any(glm::lessThan(hi[t], lo[s]))) continue;
        d3 p[3], q[3];
        for (int k2 = 0; k2 < 3; ++k2) {
          p[k2] = d3(mesh.positions[std::size_t(a[std::size_t(k2)])]);
          q[k2] = d3(mesh.positions[std::size_t(b[std::size_t(k2)])]);
        }
        bool cross = false;
        for (int e = 0; e < 3 && !cross; ++e)
          cross = pierces(p[e], p[(e + 1) % 3], q[0], q[1], q[2]) || pierces(q[e], q[(e + 1) % 3], p[0], p[1], p[2]) ||
                  distance_to_triangle(p[e], q[0], q[1], q[2]) < touching ||
                  distance_to_triangle(q[e], p[0], p[1], p[2]) < touching;
        if (cross) crossing.push_back({std::min(list[i], list[j]), std::max(list[i], list[j])});
      }
  std::sort(crossing.begin(), crossing.end());  // a pair met in several buckets counts once
  return std::int64_t(std::unique(crossing.begin(), crossing.end()) - crossing.begin());
}

}  // namespace pss::test
