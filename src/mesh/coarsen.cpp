#include "pss/mesh/coarsen.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
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
      : mesh_(mesh), cell_(cell), first_(mesh.positions.size() + 1, 0), count_(mesh.positions.size(), 0),
        alive_(mesh.triangles.size(), 1), planes_(mesh.positions.size()), weight_(mesh.positions.size(), 0.0),
        touched_(mesh.positions.size(), 0) {
    // Each vertex's triangles, a slice of list_ (counting sort by vertex).
    for (const auto& tri : mesh.triangles)
      for (int v : tri) ++first_[std::size_t(v) + 1];
    for (std::size_t v = 0; v < count_.size(); ++v) first_[v + 1] += first_[v];
    capacity_.assign(count_.size(), 0);
    for (std::size_t v = 0; v < count_.size(); ++v) capacity_[v] = int(first_[v + 1] - first_[v]);
    list_.resize(std::size_t(first_.back()));
    first_.pop_back();
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
      const auto& tri = mesh.triangles[t];
      for (int v : tri) list_[std::size_t(first_[std::size_t(v)] + count_[std::size_t(v)]++)] = int(t);
      const glm::dvec3 a = p(tri[0]), b = p(tri[1]), c = p(tri[2]);
      const glm::dvec3 area = glm::cross(b - a, c - a);
      const double length = glm::length(area);
      if (!(length > 0)) continue;
      const glm::dvec3 n = area / length;
      for (int v : tri) {
        planes_[std::size_t(v)].add_plane(n, -glm::dot(n, a), length / 6);
        weight_[std::size_t(v)] += length / 6;
      }
    }
  }

  // One pass: the short edges, shortest (against their cell) first, each collapsed where
  // neither end was removed by this pass. The first pass looks at every edge, later ones at
  // the edges of the vertices the last pass touched: the tests of a collapse read only its
  // ends' triangles, so an edge refused with neither end touched since is refused again.
  // Returns how many collapsed.
  std::int64_t pass() {
    std::vector<Candidate>& short_edges = candidates_;
    short_edges.clear();
    if (first_pass_) {
      for (std::size_t t = 0; t < mesh_.triangles.size(); ++t) add_short_edges(int(t), short_edges);
      first_pass_ = false;
    } else {
      for (const int v : touched_list_)
        for (const int t : triangles(v)) add_short_edges(t, short_edges);
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
      if (count_[std::size_t(e.a)] == 0 || count_[std::size_t(e.b)] == 0) continue;  // one collapsed
      const int removed = collapse_edge(e.a, e.b);
      if (removed < 0) continue;
      ++collapsed;
      touch(removed);
      for (int t : triangles(removed == e.a ? e.b : e.a))
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

  std::span<int> triangles(int v) {
    return {list_.data() + first_[std::size_t(v)], std::size_t(count_[std::size_t(v)])};
  }
  std::span<const int> triangles(int v) const {
    return {list_.data() + first_[std::size_t(v)], std::size_t(count_[std::size_t(v)])};
  }

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
    for (int t : triangles(v))
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

  // Collapses a into b, or else b into a, where the conditions above hold; returns the
  // vertex removed, or -1. The topology's tests are the edge's, the others each direction's.
  int collapse_edge(int a, int b) {
    ring(a, ring_a_, boundary_a_);
    ring(b, ring_b_, boundary_b_);
    std::vector<int>& opposite = scratch_;
    opposite.clear();
    for (int t : triangles(a)) {
      const auto& tri = mesh_.triangles[std::size_t(t)];
      if (tri[0] == b || tri[1] == b || tri[2] == b)
        for (int w : tri)
          if (w != a && w != b) opposite.push_back(w);
    }
    std::sort(opposite.begin(), opposite.end());
    const bool boundary_edge = std::binary_search(boundary_a_.begin(), boundary_a_.end(), b);
    if (opposite.size() != (boundary_edge ? 1u : 2u)) return -1;
    // The link condition.
    std::vector<int>& shared = shared_;
    shared.clear();
    std::set_intersection(ring_a_.begin(), ring_a_.end(), ring_b_.begin(), ring_b_.end(), std::back_inserter(shared));
    if (shared != opposite) return -1;
    if (ring_a_.size() == 3 && ring_b_.size() == 3) return -1;  // a tetrahedron
    if (may_collapse(a, b, boundary_a_, boundary_edge)) return apply(a, b), a;
    if (may_collapse(b, a, boundary_b_, boundary_edge)) return apply(b, a), b;
    return -1;
  }

  // Whether u may move onto v: its boundary, the planes it takes, its triangles' turn and shape.
  bool may_collapse(int u, int v, const std::vector<int>& boundary_u, bool boundary_edge) {
    const double tolerance = double(kCoarseningError) * double(std::min(cell_[std::size_t(u)], cell_[std::size_t(v)]));
    int w = -1;  // u's other boundary neighbour, where u is on the boundary
    if (!boundary_u.empty()) {
      // Along the boundary only, into its next vertex, with the new boundary edge v–w within
      // the tolerance of u and of every boundary vertex its two edges had taken in before.
      if (!boundary_edge || boundary_u.size() != 2 || count_[std::size_t(u)] < 2) return false;
      w = boundary_u[0] == v ? boundary_u[1] : boundary_u[0];
      if (!near_segment(p(u), v, w, tolerance)) return false;
      for (const int end : {v, w}) {
        const auto taken = rim_taken_.find(edge_key(u, end));
        if (taken == rim_taken_.end()) continue;
        for (const glm::dvec3& x : taken->second)
          if (!near_segment(x, v, w, tolerance)) return false;
      }
    }
    // The planes the vertex takes.
    Quadric planes = planes_[std::size_t(v)];
    planes.add(planes_[std::size_t(u)]);
    const double weight = weight_[std::size_t(u)] + weight_[std::size_t(v)];
    if (weight > 0 && planes.at(p(v)) > tolerance * tolerance * weight) return false;
    // The triangles that stay, with v for u.
    double worst_before = 1;
    for (int t : triangles(u)) {
      const auto& tri = mesh_.triangles[std::size_t(t)];
      worst_before = std::min(worst_before, quality(p(tri[0]), p(tri[1]), p(tri[2])));
    }
    const double least = std::min(kLeastQuality, worst_before);
    for (int t : triangles(u)) {
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
    planes_[std::size_t(v)] = planes;
    weight_[std::size_t(v)] = weight;
    if (w >= 0) {  // the boundary vertices the new edge v–w stands for
      std::vector<glm::dvec3> taken{p(u)};
      for (const int end : {v, w}) {
        const auto old = rim_taken_.find(edge_key(u, end));
        if (old == rim_taken_.end()) continue;
        taken.insert(taken.end(), old->second.begin(), old->second.end());
        rim_taken_.erase(old);
      }
      rim_taken_[edge_key(v, w)] = std::move(taken);
    }
    return true;
  }

  static std::uint64_t edge_key(int a, int b) {
    return std::uint64_t(std::uint32_t(std::min(a, b))) << 32 | std::uint32_t(std::max(a, b));
  }

  // Whether x lies within `tolerance` of the segment from vertex a to vertex b.
  bool near_segment(const glm::dvec3& x, int a, int b, double tolerance) const {
    const glm::dvec3 along = p(b) - p(a);
    const double t = std::clamp(glm::dot(x - p(a), along) / std::max(glm::dot(along, along), 1e-300), 0.0, 1.0);
    return glm::length(x - (p(a) + t * along)) <= tolerance;
  }

  // Moves u onto v: the edge's triangles go, u's others become v's.
  void apply(int u, int v) {
    std::vector<int>& moved = scratch_;
    moved.clear();
    for (int t : triangles(u)) {
      auto& tri = mesh_.triangles[std::size_t(t)];
      if (tri[0] == v || tri[1] == v || tri[2] == v) {
        alive_[std::size_t(t)] = 0;
        for (int w : tri)
          if (w != u) remove(w, t);
      } else {
        for (int& w : tri)
          if (w == u) w = v;
        moved.push_back(t);
      }
    }
    count_[std::size_t(u)] = 0;
    // v's slice grows: where it has no room, it moves to list_'s end (with room for a few more).
    const std::size_t n = std::size_t(count_[std::size_t(v)]), grown = n + moved.size();
    if (grown > std::size_t(capacity_[std::size_t(v)])) {
      const std::size_t at = list_.size();
      list_.resize(at + grown + 4);
      std::copy_n(list_.begin() + first_[std::size_t(v)], n, list_.begin() + std::ptrdiff_t(at));
      first_[std::size_t(v)] = std::int64_t(at);
      capacity_[std::size_t(v)] = int(grown + 4);
    }
    std::copy(moved.begin(), moved.end(), list_.begin() + first_[std::size_t(v)] + std::ptrdiff_t(n));
    count_[std::size_t(v)] = int(grown);
  }

  void remove(int w, int t) {
    const std::span<int> list = triangles(w);
    const auto end = std::remove(list.begin(), list.end(), t);
    count_[std::size_t(w)] = int(end - list.begin());
  }

  TriangleMesh& mesh_;
  std::span<const float> cell_;
  std::vector<std::int64_t> first_;  // each vertex's triangles: list_[first_, first_ + count_)
  std::vector<int> count_, capacity_, list_;
  std::vector<char> alive_;
  std::vector<Quadric> planes_;
  std::vector<double> weight_;
  std::vector<int> ring_a_, ring_b_, boundary_a_, boundary_b_, scratch_, shared_;
  std::vector<Candidate> candidates_;
  bool first_pass_ = true;
  std::vector<char> touched_;  // by a collapse of the last pass, as touched_list_
  // The boundary vertices each boundary edge made by collapses stands for (by its ends).
  std::map<std::uint64_t, std::vector<glm::dvec3>> rim_taken_;
  std::vector<int> touched_list_;
};

}  // namespace

void coarsen_mesh(TriangleMesh& mesh, std::span<const float> cell, MarchCounts& counts) {
  if (cell.size() != mesh.positions.size())
    throw Error("coarsen_mesh needs one cell a vertex (" + std::to_string(cell.size()) + " for " +
                std::to_string(mesh.positions.size()) + ")");
  for (const float c : cell)
    if (!(c > 0) || !std::isfinite(c)) throw Error("coarsen_mesh needs positive cells");
  Coarsening coarsening(mesh, cell);
  while (coarsening.pass() > 0) {
  }
  counts.collapsed_vertices = coarsening.finish();
  counts.normals_turned += normals_follow_winding(mesh);
}

}  // namespace pss
