#include "pss/mesh/coarsen.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <exception>
#include <map>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

#include <omp.h>

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
// The vertices of a block that one thread coarsens (Coarsening::pass): the edges whose
// triangles reach past a block's border wait for the next stage; about 5 % of them are left
// to the last, one thread, at this size (the locally refined cylinder's 2.5 M in its first pass).
constexpr std::size_t kBlockVertices = 4096;

// f(i) for i in [0, n) on `threads` OpenMP threads, `chunk` at a time; the first exception
// (a bad_alloc) is thrown again on the caller's thread, as one thread's loop would throw it.
template <class F>
void on_threads(std::int64_t n, int threads, int chunk, F&& f) {
  std::exception_ptr error;
  std::atomic<bool> failed{false};
#pragma omp parallel for schedule(dynamic, chunk) num_threads(threads)
  for (std::int64_t i = 0; i < n; ++i) {
    if (failed.load(std::memory_order_relaxed)) continue;
    try {
      f(i);
    } catch (...) {
#pragma omp critical(pss_coarsen_error)
      if (!error) error = std::current_exception();
      failed.store(true, std::memory_order_relaxed);
    }
  }
  if (error) std::rethrow_exception(error);
}

double quality(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
  const double edges = glm::dot(b - a, b - a) + glm::dot(c - b, c - b) + glm::dot(a - c, a - c);
  return edges > 0 ? 2.0 * std::sqrt(3.0) * glm::length(glm::cross(b - a, c - a)) / edges : 0.0;
}

class Coarsening {
 public:
  Coarsening(TriangleMesh& mesh, std::span<const float> cell)
      : mesh_(mesh), cell_(cell), first_(mesh.positions.size() + 1, 0), count_(mesh.positions.size(), 0),
        arena_(mesh.positions.size(), 0), alive_(mesh.triangles.size(), 1), planes_(mesh.positions.size()),
        weight_(mesh.positions.size(), 0.0), touched_(mesh.positions.size(), 0),
        scratch_(std::size_t(std::max(1, omp_get_max_threads()))) {
    if (!mesh.positions.empty()) {
      const std::vector<int> order = morton_order(mesh.positions);
      partitions_[0] = partition(order, 0, 1);
      partitions_[1] = partition(order, kBlockVertices / 2, 1 + partitions_[0].blocks);
    }
    // The march's lists, each block's growth in each partition, the sweep's.
    arenas_.resize(std::size_t(1 + partitions_[0].blocks + partitions_[1].blocks + 1));
    // Each vertex's triangles, a slice of the first arena (counting sort by vertex).
    for (const auto& tri : mesh.triangles)
      for (int v : tri) ++first_[std::size_t(v) + 1];
    for (std::size_t v = 0; v < count_.size(); ++v) first_[v + 1] += first_[v];
    capacity_.assign(count_.size(), 0);
    for (std::size_t v = 0; v < count_.size(); ++v) capacity_[v] = int(first_[v + 1] - first_[v]);
    std::vector<int>& list = arenas_[0];
    list.resize(std::size_t(first_.back()));
    first_.pop_back();
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
      for (int v : mesh.triangles[t]) list[std::size_t(first_[std::size_t(v)] + count_[std::size_t(v)]++)] = int(t);
    // Each vertex's planes, its triangles' in their order, a third of each one's area.
    on_threads(std::int64_t(count_.size()), int(scratch_.size()), 256, [&](std::int64_t v) {
      for (const int t : triangles(int(v))) {
        const auto& tri = mesh.triangles[std::size_t(t)];
        const glm::dvec3 a = p(tri[0]), b = p(tri[1]), c = p(tri[2]);
        const glm::dvec3 area = glm::cross(b - a, c - a);
        const double length = glm::length(area);
        if (!(length > 0)) continue;
        const glm::dvec3 n = area / length;
        planes_[std::size_t(v)].add_plane(n, -glm::dot(n, a), length / 6);
        weight_[std::size_t(v)] += length / 6;
      }
    });
  }

  // One pass: the short edges, shortest (against their cell) first, each collapsed where
  // neither end was removed by this pass. The first pass looks at every edge, later ones at
  // the edges of the vertices the last pass touched: the tests of a collapse read only its
  // ends' triangles, so an edge refused with neither end touched since is refused again.
  // The blocks of a partition (Partition) collapse their edges on all cores, each those whose
  // ends' triangles lie in it alone: no two blocks read or write one vertex's or triangle's
  // data, so the result is the same for any thread count. The edges left between blocks go
  // to the blocks of the shifted partition, and those left again to one thread (the sweep),
  // shortest first. Returns how many collapsed.
  std::int64_t pass() {
    const int threads = int(scratch_.size());
    std::vector<std::vector<Candidate>> found(static_cast<std::size_t>(threads));
    const auto sources = std::int64_t(first_pass_ ? mesh_.positions.size() : touched_list_.size());
    on_threads(sources, threads, 256, [&](std::int64_t i) {
      const auto thread = std::size_t(omp_get_thread_num());
      add_short_edges(first_pass_ ? int(i) : touched_list_[std::size_t(i)], !first_pass_, scratch_[thread],
                      found[thread]);
    });
    first_pass_ = false;
    for (const int v : touched_list_) touched_[std::size_t(v)] = 0;
    touched_list_.clear();
    std::vector<Candidate> left;
    std::vector<Outcome> outcome;
    for (const Partition& partition : partitions_) {
      const std::vector<std::size_t> begin = into_runs(found, partition, left);
      const auto run = [&](int k) {
        const auto from = begin[std::size_t(k)], to = begin[std::size_t(k) + 1];
        return std::span<const Candidate>(left).subspan(from, to - from);
      };
      std::vector<Outcome> done(std::size_t(partition.blocks));
      on_threads(partition.blocks, threads, 1, [&](std::int64_t b) {
        collapse_in_order(run(int(b)), &partition, int(b), scratch_[std::size_t(omp_get_thread_num())],
                          done[std::size_t(b)]);
      });
      std::vector<Candidate> between(run(partition.blocks).begin(), run(partition.blocks).end());
      for (Outcome& o : done) {
        between.insert(between.end(), o.deferred.begin(), o.deferred.end());
        outcome.push_back(std::move(o));
      }
      found.assign(1, std::move(between));
    }
    left = std::move(found[0]);
    std::sort(left.begin(), left.end(), shorter);
    outcome.emplace_back();
    collapse_in_order(left, nullptr, 0, scratch_[0], outcome.back());
    std::int64_t collapsed = 0;
    for (const Outcome& o : outcome) {
      collapsed += o.collapsed;
      touched_list_.insert(touched_list_.end(), o.touched.begin(), o.touched.end());
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
  static bool shorter(const Candidate& x, const Candidate& y) {
    return x.share != y.share ? x.share < y.share : x.a != y.a ? x.a < y.a : x.b < y.b;
  }
  // A block's collapses: how many, the vertices they touched, the edges left to the sweep.
  struct Outcome {
    std::int64_t collapsed = 0;
    std::vector<int> touched;
    std::vector<Candidate> deferred;
  };
  // One thread's working lists.
  struct Scratch {
    std::vector<int> ring_a, ring_b, boundary_a, boundary_b, opposite, shared, moved;
  };
  static constexpr int kLeftToNextStage = -2;

  // Runs of kBlockVertices vertices along the Morton order of their places in the mesh's box
  // (ties by index), from `offset` on in that order: a block is a patch of the surface. The
  // same blocks for any thread count. A block's vertices' slices grow in arenas_[arena + b].
  struct Partition {
    std::vector<int> of;  // each vertex's block
    int blocks = 0;
    int arena = 0;
  };
  static std::vector<int> morton_order(std::span<const vec3> positions) {
    vec3 lo = positions[0], hi = positions[0];
    for (const vec3& p : positions) {
      lo = glm::min(lo, p);
      hi = glm::max(hi, p);
    }
    const vec3 scale = float(1 << 20) / glm::max(hi - lo, vec3(1e-30f));
    std::vector<std::pair<std::uint64_t, int>> order(positions.size());
    for (std::size_t v = 0; v < positions.size(); ++v) {
      const vec3 c = glm::clamp((positions[v] - lo) * scale, vec3(0.0f), vec3(float((1 << 20) - 1)));
      const std::uint64_t x = std::uint64_t(c.x), y = std::uint64_t(c.y), z = std::uint64_t(c.z);
      std::uint64_t code = 0;
      for (int bit = 19; bit >= 0; --bit)
        code = (code << 3) | ((x >> bit) & 1) << 2 | ((y >> bit) & 1) << 1 | ((z >> bit) & 1);
      order[v] = {code, int(v)};
    }
    std::sort(order.begin(), order.end());
    std::vector<int> vertices(order.size());
    for (std::size_t k = 0; k < order.size(); ++k) vertices[k] = order[k].second;
    return vertices;
  }
  static Partition partition(std::span<const int> order, std::size_t offset, int arena) {
    Partition p;
    p.of.resize(order.size());
    for (std::size_t k = 0; k < order.size(); ++k) p.of[std::size_t(order[k])] = int((k + offset) / kBlockVertices);
    p.blocks = order.empty() ? 0 : int((order.size() - 1 + offset) / kBlockVertices) + 1;
    p.arena = arena;
    return p;
  }

  // The edges of `lists` (emptied) into `runs`: each block's of `partition` (both ends in
  // it), then the edges between blocks; each run shortest first. Returns the runs' starts and
  // the end. A counting sort, each list scattered by its own thread.
  std::vector<std::size_t> into_runs(std::vector<std::vector<Candidate>>& lists, const Partition& partition,
                                     std::vector<Candidate>& runs) const {
    const int between = partition.blocks, threads = int(scratch_.size());
    const auto key = [&](const Candidate& e) {
      const int a = partition.of[std::size_t(e.a)];
      return std::size_t(a == partition.of[std::size_t(e.b)] ? a : between);
    };
    const std::size_t keys = std::size_t(between) + 1;
    const auto count = std::int64_t(lists.size());
    // at[l][k]: list l's edges of run k, then where the first of them goes.
    std::vector<std::vector<std::size_t>> at(lists.size(), std::vector<std::size_t>(keys, 0));
    on_threads(count, threads, 1, [&](std::int64_t l) {
      for (const Candidate& e : lists[std::size_t(l)]) ++at[std::size_t(l)][key(e)];
    });
    std::vector<std::size_t> begin(keys + 1, 0);
    std::size_t total = 0;
    for (std::size_t k = 0; k < keys; ++k) {
      begin[k] = total;
      for (auto& list_at : at) total += std::exchange(list_at[k], total);
    }
    begin[keys] = total;
    runs.resize(total);
    on_threads(count, threads, 1, [&](std::int64_t l) {
      std::vector<std::size_t>& next = at[std::size_t(l)];
      for (const Candidate& e : lists[std::size_t(l)]) runs[next[key(e)]++] = e;
      std::vector<Candidate>().swap(lists[std::size_t(l)]);
    });
    on_threads(between + 1, threads, 1, [&](std::int64_t k) {
      std::sort(runs.begin() + std::ptrdiff_t(begin[std::size_t(k)]),
                runs.begin() + std::ptrdiff_t(begin[std::size_t(k) + 1]), shorter);
    });
    return begin;
  }

  // The edges of `edges` (sorted shortest first) collapsed one after the other: in block
  // `block` of `partition`, those whose ends' triangles it holds (the others left to the
  // next stage), or anywhere where `partition` is null (the sweep, its slices growing in the
  // last arena).
  void collapse_in_order(std::span<const Candidate> edges, const Partition* partition, int block, Scratch& s,
                         Outcome& out) {
    for (const Candidate& e : edges) {
      if (count_[std::size_t(e.a)] == 0 || count_[std::size_t(e.b)] == 0) continue;  // one collapsed
      const int removed = collapse_edge(e.a, e.b, partition, block, s);
      if (removed == kLeftToNextStage) out.deferred.push_back(e);
      if (removed < 0) continue;
      ++out.collapsed;
      touch(removed, out.touched);
      for (int t : triangles(removed == e.a ? e.b : e.a))
        for (int v : mesh_.triangles[std::size_t(t)]) touch(v, out.touched);
    }
  }

  glm::dvec3 p(int v) const { return glm::dvec3(mesh_.positions[std::size_t(v)]); }

  std::span<int> triangles(int v) {
    return {arenas_[std::size_t(arena_[std::size_t(v)])].data() + first_[std::size_t(v)],
            std::size_t(count_[std::size_t(v)])};
  }
  std::span<const int> triangles(int v) const {
    return {arenas_[std::size_t(arena_[std::size_t(v)])].data() + first_[std::size_t(v)],
            std::size_t(count_[std::size_t(v)])};
  }

  void touch(int v, std::vector<int>& touched) {
    if (touched_[std::size_t(v)]) return;
    touched_[std::size_t(v)] = 1;
    touched.push_back(v);
  }

  // The edges of v shorter than kShortEdgeShare of the finer cell of their ends (the coarse
  // side of a step in the spacing grades towards the fine one), each once: those to a
  // neighbour w of v's ring with w > v, or, where `after_touched`, w not touched (an edge
  // between two touched vertices comes from the lower).
  void add_short_edges(int v, bool after_touched, Scratch& s, std::vector<Candidate>& out) const {
    ring(v, s.ring_a, s.boundary_a);
    for (const int w : s.ring_a) {
      if (!(w > v || (after_touched && !touched_[std::size_t(w)]))) continue;
      const double cell = double(std::min(cell_[std::size_t(v)], cell_[std::size_t(w)]));
      const double share = glm::length(p(v) - p(w)) / cell;
      if (share < double(kShortEdgeShare)) out.push_back({share, std::min(v, w), std::max(v, w)});
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
  // vertex removed, or -1, or kLeftToNextStage where block `block` of `partition` (if any)
  // does not hold every vertex of their triangles. The topology's tests are the edge's, the
  // others each direction's.
  int collapse_edge(int a, int b, const Partition* partition, int block, Scratch& s) {
    ring(a, s.ring_a, s.boundary_a);
    ring(b, s.ring_b, s.boundary_b);
    if (partition) {
      const auto elsewhere = [&](int w) { return partition->of[std::size_t(w)] != block; };
      if (std::any_of(s.ring_a.begin(), s.ring_a.end(), elsewhere) ||
          std::any_of(s.ring_b.begin(), s.ring_b.end(), elsewhere))
        return kLeftToNextStage;
    }
    std::vector<int>& opposite = s.opposite;
    opposite.clear();
    for (int t : triangles(a)) {
      const auto& tri = mesh_.triangles[std::size_t(t)];
      if (tri[0] == b || tri[1] == b || tri[2] == b)
        for (int w : tri)
          if (w != a && w != b) opposite.push_back(w);
    }
    std::sort(opposite.begin(), opposite.end());
    const bool boundary_edge = std::binary_search(s.boundary_a.begin(), s.boundary_a.end(), b);
    if (opposite.size() != (boundary_edge ? 1u : 2u)) return -1;
    // The link condition.
    std::vector<int>& shared = s.shared;
    shared.clear();
    std::set_intersection(s.ring_a.begin(), s.ring_a.end(), s.ring_b.begin(), s.ring_b.end(),
                          std::back_inserter(shared));
    if (shared != opposite) return -1;
    if (s.ring_a.size() == 3 && s.ring_b.size() == 3) return -1;  // a tetrahedron
    const int arena = partition ? partition->arena + block : int(arenas_.size()) - 1;
    if (may_collapse(a, b, s.boundary_a, boundary_edge)) return apply(a, b, arena, s.moved), a;
    if (may_collapse(b, a, s.boundary_b, boundary_edge)) return apply(b, a, arena, s.moved), b;
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
      // The map is shared by the blocks, each reading and writing its own edges' entries.
      const std::lock_guard<std::mutex> lock(rim_mutex_);
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
      const std::lock_guard<std::mutex> lock(rim_mutex_);
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

  // Moves u onto v: the edge's triangles go, u's others become v's; where v's slice has no
  // room, it moves to the end of arenas_[arena] (with room for a few more).
  void apply(int u, int v, int arena, std::vector<int>& moved) {
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
    const std::size_t n = std::size_t(count_[std::size_t(v)]), grown = n + moved.size();
    if (grown > std::size_t(capacity_[std::size_t(v)])) {
      std::vector<int>& to = arenas_[std::size_t(arena)];
      const std::size_t at = to.size();
      to.resize(at + grown + 4);  // then v's old slice, which may lie in `to`
      const std::vector<int>& from = arenas_[std::size_t(arena_[std::size_t(v)])];
      std::copy_n(from.begin() + first_[std::size_t(v)], n, to.begin() + std::ptrdiff_t(at));
      arena_[std::size_t(v)] = arena;
      first_[std::size_t(v)] = std::int64_t(at);
      capacity_[std::size_t(v)] = int(grown + 4);
    }
    std::copy(moved.begin(), moved.end(),
              arenas_[std::size_t(arena_[std::size_t(v)])].begin() + first_[std::size_t(v)] + std::ptrdiff_t(n));
    count_[std::size_t(v)] = int(grown);
  }

  void remove(int w, int t) {
    const std::span<int> list = triangles(w);
    const auto end = std::remove(list.begin(), list.end(), t);
    count_[std::size_t(w)] = int(end - list.begin());
  }

  TriangleMesh& mesh_;
  std::span<const float> cell_;
  Partition partitions_[2];  // blocks, and blocks shifted by half a block
  // Each vertex's triangles: arenas_[arena_][first_, first_ + count_). Arena 0 holds the
  // march's lists; a slice that grows moves to its block's arena, or the sweep's, the last.
  std::vector<std::int64_t> first_;
  std::vector<int> count_, capacity_, arena_;
  std::vector<std::vector<int>> arenas_;
  std::vector<char> alive_;
  std::vector<Quadric> planes_;
  std::vector<double> weight_;
  bool first_pass_ = true;
  std::vector<char> touched_;  // by a collapse of the last pass, as touched_list_
  // The boundary vertices each boundary edge made by collapses stands for (by its ends).
  std::map<std::uint64_t, std::vector<glm::dvec3>> rim_taken_;
  std::mutex rim_mutex_;
  std::vector<int> touched_list_;
  std::vector<Scratch> scratch_;  // per thread
};

}  // namespace

void coarsen_mesh(TriangleMesh& mesh, std::span<const float> cell, MarchCounts& counts) {
  if (cell.size() != mesh.positions.size())
    throw Error("coarsen_mesh needs one cell a vertex (" + std::to_string(cell.size()) + " for " +
                std::to_string(mesh.positions.size()) + ")");
  for (const float c : cell)
    if (!(c > 0) || !std::isfinite(c)) throw Error("coarsen_mesh needs positive cells");
  for (const vec3& p : mesh.positions)
    if (!is_finite(p)) throw Error("coarsen_mesh needs finite vertex positions");
  Coarsening coarsening(mesh, cell);
  while (coarsening.pass() > 0) {
  }
  counts.collapsed_vertices = coarsening.finish();
  counts.normals_turned += normals_follow_winding(mesh);
}

}  // namespace pss
