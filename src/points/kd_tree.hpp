// nanoflann's k-d tree over a span of points: the k nearest neighbours that the spacing
// estimate and the adaptive support read (host only). Internal to src/points.
#pragma once

#include <nanoflann.hpp>
#include <span>

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

}  // namespace pss::points_detail
