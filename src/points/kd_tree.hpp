// nanoflann's k-d tree over a span of points: the k nearest neighbours that the spacing
// estimate and the adaptive support read (host only). Internal to src/points.
#pragma once

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
