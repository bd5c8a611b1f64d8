#include "pss/points/spacing.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "pss/core/error.hpp"
#include "kd_tree.hpp"
#include "unit_frame.hpp"

namespace pss {

using points_detail::CloudAdaptor;
using points_detail::KdTree;

SpacingEstimate estimate_spacing(std::span<const vec3> input, int k, std::size_t max_samples) {
  if (input.size() < 2) throw Error("cannot estimate the sample spacing of fewer than two points");
  // In the unit frame, so that squared distances neither overflow (1e30) nor underflow
  // (1e-30) in float; the distances are scaled back below.
  const points_detail::UnitFrame frame = points_detail::unit_frame(input);
  const std::vector<vec3> unit = points_detail::to_unit(input, frame);
  const std::span<const vec3> points(unit);
  k = std::min<int>(k, int(points.size()) - 1);
  CloudAdaptor adaptor{points};
  KdTree tree(3, adaptor, nanoflann::KDTreeSingleIndexAdaptorParams(16));
  tree.buildIndex();

  const std::size_t stride = std::max<std::size_t>(1, points.size() / max_samples);
  std::vector<unsigned> index(k + 1);
  std::vector<float> dist2(k + 1);
  std::vector<double> kth;
  double nearest_sum = 0;
  for (std::size_t i = 0; i < points.size(); i += stride) {
    // k + 1 because the query point finds itself at distance 0.
    const std::size_t found = tree.knnSearch(&points[i].x, k + 1, index.data(), dist2.data());
    nearest_sum += std::sqrt(double(dist2[std::min<std::size_t>(1, found - 1)]));
    kth.push_back(std::sqrt(double(dist2[found - 1])));
  }
  std::nth_element(kth.begin(), kth.begin() + kth.size() / 2, kth.end());
  SpacingEstimate e;
  e.k = k;
  e.mean_nearest = nearest_sum / double(kth.size()) * frame.scale;
  e.median_kth = kth[kth.size() / 2] * frame.scale;
  const auto [least, largest] = std::minmax_element(kth.begin(), kth.end());
  e.min_kth = *least * frame.scale;
  e.max_kth = *largest * frame.scale;
  e.suggested_h = e.median_kth;
  if (!(e.suggested_h > 0))
    throw Error("cannot estimate the sample spacing: the points coincide (pass --h explicitly)");
  return e;
}

float default_h(std::span<const vec3> points) {
  return points.size() < 2 ? 1.0f : float(estimate_spacing(points).suggested_h);
}

}  // namespace pss
