// nanoflann's k-d tree over a span of points: the k nearest neighbours that the spacing
// estimate and the adaptive support read (host only). Internal to src/points.
#pragma once

#include <cmath>
#include <cstdint>
#include <nanoflann.hpp>
#include <span>

#include "pss/backend/cpu/parallel_for.hpp"
#include "pss/core/types.hpp"

namespace pss::points_detail {

struct CloudAdaptor {
  std::span<const vec3> points;
  std::size_t kdtree_get_point_count() const { return points.size(); }
  float kdtree_get_pt(std::size_t i, std::size_t dim) const { return points[i][int(dim)]; }
  template <class Box>
  bool kdtree_get_bbox(Box&) const {
    return false;
  }
};

using KdTree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<float, CloudAdaptor>, CloudAdaptor, 3>;

// The `count` nearest points to `at`, nearest first, those at equal distances in the order of
// their ids (`id[i]` the id of the tree's point i; empty: i itself); returns how many. The
// tree's own order breaks ties by how it was built, so a tile and its halo would keep other
// points than the whole cloud does (issue 28: the tiles' widths are the in-core ones).
inline std::size_t nearest_by_id(const KdTree& tree, const vec3& at, std::size_t count, unsigned* index, float* d2,
                                 std::span<const std::uint64_t> id = {}) {
  struct ById {
    unsigned* index;
    float* d2;
    std::size_t capacity, count = 0;
    std::span<const std::uint64_t> id;
    std::uint64_t key(unsigned i) const { return id.empty() ? i : id[i]; }
    std::size_t size() const { return count; }
    bool full() const { return count == capacity; }
    // nanoflann adds a point only when nearer than this: a point at the last one's distance
    // may still come before it.
    float worstDist() const { return full() ? std::nextafter(d2[capacity - 1], kInfinity) : kInfinity; }
    bool addPoint(float d, unsigned i) {
      std::size_t at = count;
      while (at > 0 && (d2[at - 1] > d || (d2[at - 1] == d && key(index[at - 1]) > key(i)))) --at;
      if (at == capacity) return true;
      for (std::size_t j = std::min(count, capacity - 1); j > at; --j) index[j] = index[j - 1], d2[j] = d2[j - 1];
      index[at] = i, d2[at] = d;
      count = std::min(count + 1, capacity);
      return true;
    }
  } result{index, d2, count, 0, id};
  if (count == 0) return 0;
  tree.findNeighbors(result, &at.x, nanoflann::SearchParams());
  return result.count;
}

// f(i) for every point of the tree, on all cores, in the order of its leaves: queries one
// after another then walk the same nodes and read the same points, from the cache. In a
// cloud's own order (a generator's random one), the adaptive support's k-NN passes took
// 1.7x as long at 10^6 points (issue 28).
template <class F>
void parallel_for_in_tree_order(const KdTree& tree, F&& f, Progress* progress = nullptr) {
  cpu::parallel_for(std::int64_t(tree.vAcc.size()), [&](std::int64_t t) { f(std::int64_t(tree.vAcc[std::size_t(t)])); },
                    progress);
}

}  // namespace pss::points_detail
