#include "pss/points/support.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "pss/backend/cpu/parallel_for.hpp"
#include "pss/core/error.hpp"
#include "pss/core/progress.hpp"
#include "kd_tree.hpp"
#include "unit_frame.hpp"

namespace pss {

namespace {

// For every point, the median of d_k over it and its k nearest neighbours, d_k(j) the distance
// from p_j to its k-th nearest other sample. The median, not p_i's own d_k: a stray sample
// far from the rest has a large d_k but takes its neighbours' width, which leaves it too few
// samples to make a surface of its own (no floating blob); and widths vary smoothly, so the
// surface does not pucker where two neighbours' widths differ by chance.
std::vector<float> neighbourhood_spacing(std::span<const vec3> input, int k) {
  const points_detail::UnitFrame frame = points_detail::unit_frame(input);
  const std::vector<vec3> unit = points_detail::to_unit(input, frame);
  const points_detail::CloudAdaptor adaptor{unit};
  points_detail::KdTree tree(3, adaptor, nanoflann::KDTreeSingleIndexAdaptorParams(16));
  tree.buildIndex();
  const auto n = std::int64_t(unit.size());
  std::vector<float> own(unit.size()), out(unit.size());
  Progress progress("support widths", 2 * n);
  // k + 1 below: each query finds its own point at distance 0.
  cpu::parallel_for(n, [&](std::int64_t i) {
    unsigned index[kSupportNeighbour + 1];
    float d2[kSupportNeighbour + 1];
    const std::size_t found = tree.knnSearch(&unit[std::size_t(i)].x, std::size_t(k + 1), index, d2);
    // A sample of a small cluster, apart from the rest, finds its 15th neighbour beyond the
    // gap: on an even sampling d_15 ≈ 1.4·d_8, so more than 2·d_8 is a gap, not spacing.
    const std::size_t eighth = std::min<std::size_t>(8, found - 1);
    own[std::size_t(i)] = float(std::min(std::sqrt(double(d2[found - 1])), 2 * std::sqrt(double(d2[eighth]))));
  }, &progress);
  cpu::parallel_for(n, [&](std::int64_t i) {
    unsigned index[kSupportNeighbour + 1];
    float d2[kSupportNeighbour + 1];
    const std::size_t found = tree.knnSearch(&unit[std::size_t(i)].x, std::size_t(k + 1), index, d2);
    float d[kSupportNeighbour + 1];
    for (std::size_t j = 0; j < found; ++j) d[j] = own[index[j]];
    std::nth_element(d, d + found / 2, d + found);
    out[std::size_t(i)] = float(double(d[found / 2]) * frame.scale);
  }, &progress);
  return out;
}

}  // namespace

SupportWidths support_widths(std::span<const vec3> points, const ProjectionParams& params) {
  const float h = params.h;
  if (!(h > 0) || !std::isfinite(h)) throw Error("h must be a positive number (got " + std::to_string(h) + ")");
  SupportWidths out;
  out.least = out.median = out.largest = h;
  out.h.assign(points.size(), h);
  const int k = std::min<int>(kSupportNeighbour, int(points.size()) - 1);
  if (params.support == Support::global || k < 1) return out;

  const std::vector<float> d = neighbourhood_spacing(points, k);
  std::vector<float> sorted = d;
  std::nth_element(sorted.begin(), sorted.begin() + std::ptrdiff_t(sorted.size() / 2), sorted.end());
  const float median_d = sorted[sorted.size() / 2];
  if (!(median_d > 0)) return out;  // most samples coincide with k others: no spacing to follow

  // Never narrower than h: where the cloud is denser than its median the paper's width stays
  // (a narrower one only shows the scanner's noise and opens holes where dense rows leave
  // gaps); where it is sparser the width grows with the spacing (kSupportWidening), up to
  // kSupportSpread·h and to ρ_i within the cloud's diagonal.
  const double diagonal = points_detail::unit_frame(points).diagonal;
  const float widest = std::max(h, std::min(h * kSupportSpread, float(diagonal * double(h) / double(params.rho))));
  out.least = kInfinity;
  out.largest = 0;
  for (std::size_t i = 0; i < d.size(); ++i) {
    out.h[i] = std::clamp(kSupportWidening * h * (d[i] / median_d), h, widest);
    out.least = std::min(out.least, out.h[i]);
    out.largest = std::max(out.largest, out.h[i]);
  }
  sorted = out.h;
  std::nth_element(sorted.begin(), sorted.begin() + std::ptrdiff_t(sorted.size() / 2), sorted.end());
  out.median = sorted[sorted.size() / 2];
  return out;
}

}  // namespace pss
