#include "pss/mesh/coarsen.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include <glm/ext/vector_double3.hpp>
#include <glm/geometric.hpp>

#include "pss/core/error.hpp"

namespace pss {

namespace {

// Σ w (n·x + d)² over planes, as its ten coefficients: the symmetric 4×4 matrix of Garland
// and Heckbert's quadric.
struct Quadric {
  double a[10] = {};
  void add_plane(const glm::dvec3& n, double d, double w) {
    const double p[4] = {n.x, n.y, n.z, d};
    int k = 0;
    for (int i = 0; i < 4; ++i)
      for (int j = i; j < 4; ++j) a[k++] += w * p[i] * p[j];
  }
  void add(const Quadric& o) {
    for (int k = 0; k < 10; ++k) a[k] += o.a[k];
  }
  double at(const glm::dvec3& x) const {
    const double p[4] = {x.x, x.y, x.z, 1.0};
    double sum = 0;
    int k = 0;
    for (int i = 0; i < 4; ++i)
      for (int j = i; j < 4; ++j) sum += (i == j ? 1.0 : 2.0) * a[k++] * p[i] * p[j];
    return sum;
  }
};

// A triangle no collapse may leave worse shaped than this (4√3·area / Σ edge², 1 when
// equilateral), unless one it replaces was already.
constexpr double kLeastQuality = 0.15;
// A triangle may turn at most 60° in a collapse.
constexpr double kMostTurnCosine = 0.5;

double quality(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
  const double edges = glm::dot(b - a, b - a) + glm::dot(c - b, c - b) + glm::dot(a - c, a - c);
  return edges > 0 ? 2.0 * std::sqrt(3.0) * glm::length(glm::cross(b - a, c - a)) / edges : 0.0;
}

class Coarsening {
 public:
  Coarsening(TriangleMesh& mesh, std::span<const float> cell)
      : mesh_(mesh), cell_(cell), at_(mesh.positions.size()), alive_(mesh.triangles.size(), 1),
        planes_(mesh.positions.size()), weight_(mesh.positions.size(), 0.0),
        touched_(mesh.positions.size(), 0) {
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
      const auto& tri = mesh.triangles[t];
      const glm::dvec3 a = p(tri[0]), b = p(tri[1]), c = p(tri[2]);
      const glm::dvec3 area = glm::cross(b - a, c - a);
      const double length = glm::length(area);
      for (int v : tri) at_[std::size_t(v)].push_back(int(t));
      if (!(length > 0)) continue;
      const glm::dvec3 n = area / length;
      for (int v : tri) {
        planes_[std::size_t(v)].add_plane(n, -glm::dot(n, a), length / 6);
        weight_[std::size_t(v)] += length / 6;
      }
    }
  }

  // One pass: the short edges, shortest (against their cell) first, each collapsed where
  // neither end was touched by a collapse of this pass. The first pass looks at every edge,
  // later ones at the edges of the vertices the last pass touched: the tests of a collapse
  // read only its ends' triangles, so an edge refused with neither end touched since is
  // refused again. Returns how many collapsed.
  std::int64_t pass() {
    std::vector<Candidate>& short_edges = candidates_;
    short_edges.clear();
    if (first_pass_) {
      for (std::size_t t = 0; t < mesh_.triangles.size(); ++t) add_short_edges(int(t), short_edges);
      first_pass_ = false;
    } else {
      for (const int v : touched_list_)
        for (const int t : at_[std::size_t(v)]) add_short_edges(t, short_edges);
    }
    for (const int v : touched_list_) touched_[std::size_t(v)] = 0;
    touched_list_.clear();
    std::sort(short_edges.begin(), short_edges.end(), [](const Candidate& x, const Candidate& y) {
      return x.share != y.share ? x.share < y.share : x.a != y.a ? x.a < y.a : x.b < y.b;
    });
    std::int64_t collapsed = 0;
    for (std::size_t i = 0; i < short_edges.size(); ++i) {
      const Candidate& e = short_edges[i];
      if (i > 0 && e.a == short_edges[i - 1].a && e.b == short_edges[i - 1].b) continue;
      if (at_[std::size_t(e.a)].empty() || at_[std::size_t(e.b)].empty()) continue;  // one collapsed
      const int removed = collapse(e.a, e.b) ? e.a : collapse(e.b, e.a) ? e.b : -1;
      if (removed < 0) continue;
      ++collapsed;
      touch(removed);
      for (int t : at_[std::size_t(removed == e.a ? e.b : e.a)])
        for (int v : mesh_.triangles[std::size_t(t)]) touch(v);
    }
    return collapsed;
  }

  // The mesh of the triangles left; returns the vertices removed.
  std::int64_t finish() {
    std::vector<std::array<int, 3>> kept;
    kept.reserve(mesh_.triangles.size());
    for (std::size_t t = 0; t < mesh_.triangles.size(); ++t)
      if (alive_[t]) kept.push_back(mesh_.triangles[t]);
    mesh_.triangles.swap(kept);
    const std::size_t before = mesh_.positions.size();
    drop_unused_vertices(mesh_);
    return std::int64_t(before - mesh_.positions.size());
  }

 private:
  struct Candidate {
    double share;
    int a, b;
  };

  glm::dvec3 p(int v) const { return glm::dvec3(mesh_.positions[std::size_t(v)]); }

  void touch(int v) {
    if (touched_[std::size_t(v)]) return;
    touched_[std::size_t(v)] = 1;
    touched_list_.push_back(v);
  }

  // Triangle t's edges shorter than kShortEdgeShare of the finer cell of their ends (the
  // coarse side of a step in the spacing grades towards the fine one).
  void add_short_edges(int t, std::vector<Candidate>& out) const {
    if (!alive_[std::size_t(t)]) return;
    const auto& tri = mesh_.triangles[std::size_t(t)];
    for (int k = 0; k < 3; ++k) {
      const int a = tri[std::size_t(k)], b = tri[std::size_t((k + 1) % 3)];
      const double cell = double(std::min(cell_[std::size_t(a)], cell_[std::size_t(b)]));
      const double share = glm::length(p(a) - p(b)) / cell;
      if (share < double(kShortEdgeShare)) out.push_back({share, std::min(a, b), std::max(a, b)});
    }
  }

  // The vertices sharing a triangle with v, sorted, and those of them on one of v's
  // triangles only (v's boundary neighbours).
  void ring(int v, std::vector<int>& all, std::vector<int>& boundary) const {
    all.clear();
    for (int t : at_[std::size_t(v)])
      for (int w : mesh_.triangles[std::size_t(t)])
        if (w != v) all.push_back(w);
    std::sort(all.begin(), all.end());
    boundary.clear();
    for (std::size_t i = 0; i < all.size();) {
      std::size_t j = i;
      while (j < all.size() && all[j] == all[i]) ++j;
      if (j - i == 1) boundary.push_back(all[i]);
      i = j;
    }
    all.erase(std::unique(all.begin(), all.end()), all.end());
  }

  // Collapses u into v where the conditions above hold.
  bool collapse(int u, int v) {
    ring(u, ring_u_, boundary_u_);
    ring(v, ring_v_, boundary_v_);
    std::vector<int>& opposite = scratch_;
    opposite.clear();
    for (int t : at_[std::size_t(u)]) {
      const auto& tri = mesh_.triangles[std::size_t(t)];
      if (tri[0] == v || tri[1] == v || tri[2] == v)
        for (int w : tri)
          if (w != u && w != v) opposite.push_back(w);
    }
    std::sort(opposite.begin(), opposite.end());
    const bool boundary_edge = std::binary_search(boundary_u_.begin(), boundary_u_.end(), v);
    if (opposite.size() != (boundary_edge ? 1u : 2u)) return false;
    if (!boundary_u_.empty()) {
      // Along the boundary only, into its next vertex, with the boundary kept straight there.
      if (!boundary_edge || boundary_u_.size() != 2 || at_[std::size_t(u)].size() < 2) return false;
      const int w = boundary_u_[0] == v ? boundary_u_[1] : boundary_u_[0];
      const glm::dvec3 along = p(w) - p(v);
      const double t = std::clamp(glm::dot(p(u) - p(v), along) / std::max(glm::dot(along, along), 1e-300), 0.0, 1.0);
      const double tolerance = double(kCoarseningError) * double(std::min(cell_[std::size_t(u)], cell_[std::size_t(v)]));
      if (glm::length(p(u) - (p(v) + t * along)) > tolerance) return false;
    }
    // The link condition.
    std::vector<int>& shared = shared_;
    shared.clear();
    std::set_intersection(ring_u_.begin(), ring_u_.end(), ring_v_.begin(), ring_v_.end(), std::back_inserter(shared));
    if (shared != opposite) return false;
    if (ring_u_.size() == 3 && ring_v_.size() == 3) return false;  // a tetrahedron
    // The planes the vertex takes.
    Quadric planes = planes_[std::size_t(v)];
    planes.add(planes_[std::size_t(u)]);
    const double weight = weight_[std::size_t(u)] + weight_[std::size_t(v)];
    const double tolerance = double(kCoarseningError) * double(std::min(cell_[std::size_t(u)], cell_[std::size_t(v)]));
    if (weight > 0 && planes.at(p(v)) > tolerance * tolerance * weight) return false;
    // The triangles that stay, with v for u.
    double worst_before = 1;
    for (int t : at_[std::size_t(u)]) {
      const auto& tri = mesh_.triangles[std::size_t(t)];
      worst_before = std::min(worst_before, quality(p(tri[0]), p(tri[1]), p(tri[2])));
    }
    const double least = std::min(kLeastQuality, worst_before);
    for (int t : at_[std::size_t(u)]) {
      const auto& tri = mesh_.triangles[std::size_t(t)];
      if (tri[0] == v || tri[1] == v || tri[2] == v) continue;
      glm::dvec3 before[3], after[3];
      for (int k = 0; k < 3; ++k) {
        before[k] = p(tri[std::size_t(k)]);
        after[k] = tri[std::size_t(k)] == u ? p(v) : before[k];
      }
      const glm::dvec3 n0 = glm::cross(before[1] - before[0], before[2] - before[0]);
      const glm::dvec3 n1 = glm::cross(after[1] - after[0], after[2] - after[0]);
      const double l0 = glm::length(n0), l1 = glm::length(n1);
      if (!(l1 > 0) || !(l0 > 0) || glm::dot(n0, n1) < kMostTurnCosine * l0 * l1) return false;
      if (quality(after[0], after[1], after[2]) < least) return false;
    }
    for (int t : at_[std::size_t(u)]) {
      auto& tri = mesh_.triangles[std::size_t(t)];
      if (tri[0] == v || tri[1] == v || tri[2] == v) {
        alive_[std::size_t(t)] = 0;
        for (int w : tri)
          if (w != u) std::erase(at_[std::size_t(w)], t);
      } else {
        for (int& w : tri)
          if (w == u) w = v;
        at_[std::size_t(v)].push_back(t);
      }
    }
    at_[std::size_t(u)].clear();
    planes_[std::size_t(v)] = planes;
    weight_[std::size_t(v)] = weight;
    return true;
  }

  TriangleMesh& mesh_;
  std::span<const float> cell_;
  std::vector<std::vector<int>> at_;  // each vertex's triangles
  std::vector<char> alive_;
  std::vector<Quadric> planes_;
  std::vector<double> weight_;
  std::vector<int> ring_u_, ring_v_, boundary_u_, boundary_v_, scratch_, shared_;
  std::vector<Candidate> candidates_;
  bool first_pass_ = true;
  std::vector<char> touched_;  // by a collapse of the last pass, as touched_list_
  std::vector<int> touched_list_;
};

}  // namespace

std::int64_t coarsen_mesh(TriangleMesh& mesh, std::span<const float> cell) {
  if (cell.size() != mesh.positions.size())
    throw Error("coarsen_mesh needs one cell a vertex (" + std::to_string(cell.size()) + " for " +
                std::to_string(mesh.positions.size()) + ")");
  for (const float c : cell)
    if (!(c > 0) || !std::isfinite(c)) throw Error("coarsen_mesh needs positive cells");
  Coarsening coarsening(mesh, cell);
  while (coarsening.pass() > 0) {
  }
  return coarsening.finish();
}

}  // namespace pss
