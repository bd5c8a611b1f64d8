#include "pss/points/support.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "pss/backend/cpu/parallel_for.hpp"
#include "pss/core/error.hpp"
#include "pss/core/median.hpp"
#include "pss/core/progress.hpp"
#include "pss/spatial/uniform_grid.hpp"
#include "kd_tree.hpp"
#include "rows.hpp"
#include "pss/points/spacing.hpp"
#include "pss/points/unit_frame.hpp"

namespace pss {

namespace {

// The smallest eigenvalue of a symmetric 3×3 matrix over its trace (Smith 1961), for the
// surface variation of kVolumeNeighbour neighbours.
double surface_variation(const double c[6]) {  // xx, yy, zz, xy, xz, yz
  const double trace = c[0] + c[1] + c[2];
  if (!(trace > 0)) return 0;
  const double q = trace / 3, off = c[3] * c[3] + c[4] * c[4] + c[5] * c[5];
  const double p2 = (c[0] - q) * (c[0] - q) + (c[1] - q) * (c[1] - q) + (c[2] - q) * (c[2] - q) + 2 * off;
  if (!(p2 > 1e-30 * trace * trace)) return 1.0 / 3;  // isotropic
  const double p = std::sqrt(p2 / 6);
  const double b0 = (c[0] - q) / p, b1 = (c[1] - q) / p, b2 = (c[2] - q) / p;
  const double bxy = c[3] / p, bxz = c[4] / p, byz = c[5] / p;
  const double det = b0 * (b1 * b2 - byz * byz) - bxy * (bxy * b2 - byz * bxz) + bxz * (bxy * byz - b1 * bxz);
  const double phi = std::acos(std::clamp(det / 2, -1.0, 1.0)) / 3;
  return std::max(0.0, q + 2 * p * std::cos(phi + 2.0943951023931957)) / trace;
}

// For every point, the median of d_k over it and its k nearest neighbours, d_k(j) the distance
// from p_j to its k-th nearest other sample. The median, not p_i's own d_k: a stray sample
// far from the rest has a large d_k but takes its neighbours' width, which leaves it too few
// samples to make a surface of its own (no floating blob); and widths vary smoothly, so the
// surface does not pucker where two neighbours' widths differ by chance. Beside it, the least
// d_k of p_i's neighbours over that median (kSparseEvenness). In a cloud sampled in rows
// (rows.hpp) a row's sample takes the distance to the next row for its d_k; the widths then
// widen against the median of the plain d_k, what h was estimated from.
struct NeighbourhoodSpacing {
  std::vector<float> spacing;  // s_i, in the input's units
  std::vector<float> least;    // min over the k nearest neighbours of d_k, over s_i
  float rows_median = 0;       // in a cloud of rows, the median of the plain d_k (input units); else 0
};

NeighbourhoodSpacing neighbourhood_spacing(std::span<const vec3> unit, double scale, const points_detail::KdTree& tree,
                                           int k) {
  const auto n = std::int64_t(unit.size());
  std::vector<float> own(unit.size()), wide(unit.size());
  NeighbourhoodSpacing out{std::vector<float>(unit.size()), std::vector<float>(unit.size())};
  Progress progress("support widths", 2 * n);
  // 2k + 1 below: each query finds its own point at distance 0; the 2k-th nearest tells a
  // row from a surface (rows.hpp).
  points_detail::parallel_for_in_tree_order(tree, [&](std::int64_t i) {
    unsigned index[2 * kSupportNeighbour + 1];
    float d2[2 * kSupportNeighbour + 1];
    const std::size_t found = tree.knnSearch(&unit[std::size_t(i)].x, std::size_t(2 * k + 1), index, d2);
    // A sample of a small cluster, apart from the rest, finds its 15th neighbour beyond the
    // gap: on an even sampling d_15 ≈ 1.4·d_8, so more than 2·d_8 is a gap, not spacing.
    const std::size_t kth = std::min<std::size_t>(std::size_t(k), found - 1);
    const std::size_t eighth = std::min<std::size_t>(8, found - 1);
    own[std::size_t(i)] = float(std::min(std::sqrt(double(d2[kth])), 2 * std::sqrt(double(d2[eighth]))));
    wide[std::size_t(i)] = std::sqrt(d2[found - 1]);
  }, &progress);
  const std::vector<float> gaps = points_detail::row_gaps(unit, tree, own, wide);
  if (!gaps.empty()) {
    out.rows_median = float(double(median_of(own)) * scale);
    for (std::size_t i = 0; i < own.size(); ++i) own[i] = std::max(own[i], gaps[i]);
  }
  points_detail::parallel_for_in_tree_order(tree, [&](std::int64_t i) {
    unsigned index[kSupportNeighbour + 1];
    float d2[kSupportNeighbour + 1];
    const std::size_t found = tree.knnSearch(&unit[std::size_t(i)].x, std::size_t(k + 1), index, d2);
    float d[kSupportNeighbour + 1], least = kInfinity;
    for (std::size_t j = 0; j < found; ++j) {
      d[j] = own[index[j]];
      if (index[j] != unsigned(i)) least = std::min(least, d[j]);
    }
    std::nth_element(d, d + found / 2, d + found);
    out.spacing[std::size_t(i)] = float(double(d[found / 2]) * scale);
    out.least[std::size_t(i)] = d[found / 2] > 0 ? least / d[found / 2] : 1.0f;
  }, &progress);
  return out;
}

// Whether p_i's kVolumeNeighbour nearest neighbours fill a volume (kVolumeVariation).
bool fills_a_volume(std::span<const vec3> unit, const points_detail::KdTree& tree, std::size_t i) {
  unsigned index[kVolumeNeighbour + 1];
  float d2[kVolumeNeighbour + 1];
  const std::size_t found = tree.knnSearch(&unit[i].x, std::size_t(kVolumeNeighbour + 1), index, d2);
  glm::dvec3 mean(0.0);
  for (std::size_t j = 0; j < found; ++j) mean += glm::dvec3(unit[index[j]]);
  mean /= double(found);
  double c[6] = {0, 0, 0, 0, 0, 0};
  for (std::size_t j = 0; j < found; ++j) {
    const glm::dvec3 d = glm::dvec3(unit[index[j]]) - mean;
    c[0] += d.x * d.x, c[1] += d.y * d.y, c[2] += d.z * d.z, c[3] += d.x * d.y, c[4] += d.x * d.z, c[5] += d.y * d.z;
  }
  return surface_variation(c) > kVolumeVariation;
}

// The noise about each sample (support.hpp, kRegionQueries), in the unit frame.
std::vector<float> regional_noise(std::span<const vec3> unit, int k) {
  // σ at every stride-th sample, as the estimate of h measures it (spacing.hpp); none (0)
  // where a query measured none: two sheets, a volume, too few neighbours.
  const UniformGrid grid(unit, 1e-7f, std::max<long long>(4096, (long long)unit.size()));
  const GridView view = grid.view();
  const float cell = 1.0f / view.inv_cell;
  const std::size_t stride = noise_query_stride(unit.size());
  std::vector<vec3> at((unit.size() + stride - 1) / stride);
  std::vector<float> measured(at.size());
  cpu::parallel_for(std::int64_t(at.size()), [&](std::int64_t q) {
    at[std::size_t(q)] = unit[std::size_t(q) * stride];
    const double sigma = query_spacing(view, cell, at[std::size_t(q)], k, true).noise;
    measured[std::size_t(q)] = std::isfinite(sigma) ? float(sigma) : 0.0f;
  });
  const points_detail::CloudAdaptor adaptor{at};
  points_detail::KdTree tree(3, adaptor, nanoflann::KDTreeSingleIndexAdaptorParams(16));
  tree.buildIndex();
  // A query's σ stands where kRegionShare of the queries within the support it asks for
  // (ρ = 2·kNoiseWidths·σ), and at least its kRegionQueries nearest, measured at least half
  // as much.
  std::vector<float> regional(at.size(), 0.0f);
  cpu::parallel_for(std::int64_t(at.size()), [&](std::int64_t q) {
    const float sigma = measured[std::size_t(q)];
    if (!(sigma > 0)) return;
    unsigned index[kRegionQueries];
    float d2[kRegionQueries];
    const std::size_t found = tree.knnSearch(&at[std::size_t(q)].x, kRegionQueries, index, d2);
    const float reach = std::max(float(2 * kNoiseWidths) * sigma, std::sqrt(d2[found - 1]));
    thread_local std::vector<std::pair<unsigned, float>> around;
    around.clear();
    tree.radiusSearch(&at[std::size_t(q)].x, reach * reach * (1 + 1e-5f), around, nanoflann::SearchParams());
    std::size_t alike = 0;
    for (const auto& other : around) alike += measured[other.first] >= 0.5f * sigma;
    if (double(alike) >= kRegionShare * double(around.size())) regional[std::size_t(q)] = sigma;
  });
  // Each region's σ spreads over the support it asks for, so that the region's edge, whose
  // queries fall short of the share, is widened too.
  std::vector<float> spread = regional;
  for (std::size_t q = 0; q < at.size(); ++q) {
    if (!(regional[q] > 0)) continue;
    const float reach = float(2 * kNoiseWidths) * regional[q];
    thread_local std::vector<std::pair<unsigned, float>> around;
    around.clear();
    tree.radiusSearch(&at[q].x, reach * reach, around, nanoflann::SearchParams());
    for (const auto& other : around) spread[other.first] = std::max(spread[other.first], regional[q]);
  }
  std::vector<float> out(unit.size(), 0.0f);
  cpu::parallel_for(std::int64_t(unit.size()), [&](std::int64_t i) {
    unsigned index[kRegionQueries];
    float d2[kRegionQueries];
    const std::size_t found = tree.knnSearch(&unit[std::size_t(i)].x, kRegionQueries, index, d2);
    for (std::size_t j = 0; j < found; ++j) out[std::size_t(i)] = std::max(out[std::size_t(i)], spread[index[j]]);
  });
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

  const UnitFrame frame = unit_frame(points);
  const std::vector<vec3> unit = to_unit(points, frame);
  const points_detail::CloudAdaptor adaptor{unit};
  points_detail::KdTree tree(3, adaptor, nanoflann::KDTreeSingleIndexAdaptorParams(16));
  tree.buildIndex();
  const NeighbourhoodSpacing spacing = neighbourhood_spacing(unit, frame.scale, tree, k);
  const std::vector<float>& d = spacing.spacing;
  const float median_d = spacing.rows_median > 0 ? spacing.rows_median : median_of(d);
  if (!(median_d > 0)) return out;  // most samples coincide with k others: no spacing to follow

  // Never narrower than h: where the cloud is denser than its median the paper's width stays
  // (a narrower one only shows the scanner's noise and opens holes where dense rows leave
  // gaps); where it is sparser the width grows with the spacing (kSupportWidening), up to
  // kSupportSpread·h and to ρ_i within the cloud's diagonal, on a sparse surface.
  const float widest =
      std::max(h, std::min(h * kSupportSpread, float(frame.diagonal * double(h) / double(params.rho))));
  // A sample widens where it lies on a sparse surface (support.hpp): sparse, with no denser
  // sample among its neighbours, flat, and kSparseNeighbours of its neighbours alike.
  std::vector<char> sparse(points.size(), 0), wide(points.size(), 0);
  points_detail::parallel_for_in_tree_order(tree, [&](std::int64_t i) {
    const auto j = std::size_t(i);
    sparse[j] = kSupportWidening * d[j] > median_d && spacing.least[j] >= kSparseEvenness &&
                !fills_a_volume(unit, tree, j);
  });
  points_detail::parallel_for_in_tree_order(tree, [&](std::int64_t i) {
    if (!sparse[std::size_t(i)]) return;
    unsigned index[kSupportNeighbour + 1];
    float d2[kSupportNeighbour + 1];
    const std::size_t found = tree.knnSearch(&unit[std::size_t(i)].x, std::size_t(k + 1), index, d2);
    int alike = 0;
    for (std::size_t j = 0; j < found; ++j) alike += index[j] != unsigned(i) && sparse[index[j]];
    wide[std::size_t(i)] = alike >= kSparseNeighbours;
  });
  const std::vector<float> noise = regional_noise(unit, k);
  out.least = kInfinity;
  out.largest = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (wide[i]) out.h[i] = std::clamp(kSupportWidening * h * (d[i] / median_d), h, widest);
    out.h[i] = std::max(out.h[i], std::min(widest, float(kNoiseWidths * double(noise[i]) * frame.scale)));
    out.least = std::min(out.least, out.h[i]);
    out.largest = std::max(out.largest, out.h[i]);
  }
  out.median = median_of(out.h);
  return out;
}

}  // namespace pss
