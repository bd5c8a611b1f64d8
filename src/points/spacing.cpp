#include "pss/points/spacing.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "pss/backend/cpu/parallel_for.hpp"
#include "pss/core/error.hpp"
#include "pss/core/median.hpp"
#include "pss/spatial/uniform_grid.hpp"
#include "pss/points/noise.hpp"
#include "pss/points/unit_frame.hpp"

namespace pss {

SpacingEstimate estimate_spacing(std::span<const vec3> input, int k, std::size_t max_samples) {
  if (input.size() < 2) throw Error("cannot estimate the sample spacing of fewer than two points");
  // In the unit frame, so that squared distances neither overflow (1e30) nor underflow
  // (1e-30) in float; the distances are scaled back below.
  const UnitFrame frame = unit_frame(input);
  const std::vector<vec3> unit = to_unit(input, frame);
  const std::span<const vec3> points(unit);
  k = std::min<int>(k, int(points.size()) - 1);
  // A uniform grid of about one cell per point, built in one counting sort: a k-d tree of
  // every point took 14 s to build at 10^7 points, for 20,000 queries (issue 28).
  const UniformGrid grid(points, 1e-7f, std::max<long long>(4096, (long long)points.size()));
  const GridView view = grid.view();
  const float cell = 1.0f / view.inv_cell;

  const std::size_t stride = spacing_stride(points.size(), max_samples);
  const std::size_t queries = (points.size() + stride - 1) / stride;
  std::vector<QuerySpacing> results(queries);
  const std::size_t noise_stride = noise_query_stride(queries);
  const NoiseGrids noise(points, view);
  cpu::parallel_for(std::int64_t(queries), [&](std::int64_t q) {
    const auto query = std::size_t(q);
    results[query] = query_spacing(view, cell, points[query * stride], k, query % noise_stride == 0 ? &noise.views() : nullptr);
  });
  return spacing_of(results, k, frame.scale);
}

std::size_t spacing_stride(std::size_t points, std::size_t max_samples) {
  return std::max<std::size_t>(1, points / max_samples);
}

std::size_t noise_query_stride(std::size_t queries) {
  return std::max<std::size_t>(1, queries / kNoiseQueries);
}

QuerySpacing query_spacing(const GridView& view, float cell, vec3 c, int k, const NoiseViews* noise) {
  thread_local std::vector<float> d2;
  // A ball that doubles until it holds k + 1 points (the query's own among them, at
  // distance 0): the k nearest of those are the k nearest of all.
  for (float r = cell;; r *= 2) {
    d2.clear();
    view.for_each_in_radius(c, r, [&](vec3, float d, int) { d2.push_back(d); });
    if (d2.size() > std::size_t(k)) break;
  }
  std::partial_sort(d2.begin(), d2.begin() + k + 1, d2.end());
  const double kth = std::sqrt(double(d2[std::size_t(k)]));
  const double nearest = std::sqrt(double(d2[std::size_t(std::min(1, k))]));
  if (!noise) return {nearest, kth, std::numeric_limits<double>::quiet_NaN(), kth};
  const QueryNoise n = noise_near(*noise, c, kth);
  return {nearest, kth, n.sigma, std::max(kth, n.reach)};
}

SpacingEstimate spacing_of(const std::vector<QuerySpacing>& queries, int k, double scale) {
  double nearest_sum = 0;
  std::vector<double> kth, noise;
  kth.reserve(queries.size());
  for (const QuerySpacing& q : queries) {
    nearest_sum += q.nearest;
    kth.push_back(q.kth);
    if (std::isfinite(q.noise)) noise.push_back(q.noise);
  }
  SpacingEstimate e;
  e.k = k;
  e.mean_nearest = nearest_sum / double(kth.size()) * scale;
  e.median_kth = median_of(kth) * scale;
  const auto [least, largest] = std::minmax_element(kth.begin(), kth.end());
  e.min_kth = *least * scale;
  e.max_kth = *largest * scale;
  e.noise = median_of(noise) * scale;
  e.suggested_h = std::max(e.median_kth, kNoiseWidths * e.noise);
  if (!(e.suggested_h > 0))
    throw Error("cannot estimate the sample spacing: the points coincide, or nearly all do beside a few very far from "
                "the rest (remove those)");
  return e;
}

float default_h(std::span<const vec3> points) {
  return points.size() < 2 ? 1.0f : float(estimate_spacing(points).suggested_h);
}

}  // namespace pss
