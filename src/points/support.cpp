#include "pss/points/support.hpp"

#include "pss/points/support_steps.hpp"

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
#include "pss/points/noise.hpp"
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

// Whether p_i's kVolumeNeighbour nearest neighbours fill a volume (kVolumeVariation).
bool fills_a_volume(std::span<const vec3> unit, std::span<const unsigned> index) {
  glm::dvec3 mean(0.0);
  for (unsigned j : index) mean += glm::dvec3(unit[j]);
  mean /= double(index.size());
  double c[6] = {0, 0, 0, 0, 0, 0};
  for (unsigned j : index) {
    const glm::dvec3 d = glm::dvec3(unit[j]) - mean;
    c[0] += d.x * d.x, c[1] += d.y * d.y, c[2] += d.z * d.z, c[3] += d.x * d.y, c[4] += d.x * d.z, c[5] += d.y * d.z;
  }
  return surface_variation(c) > kVolumeVariation;
}

// The noise queries' σ, measured as the estimate of h measures it (spacing.hpp), in the
// unit frame; none (0) where a query measured none: two sheets, a volume, too few neighbours.
RegionalNoise regional_noise(std::span<const vec3> unit, int k) {
  const UniformGrid grid(unit, 1e-7f, std::max<long long>(4096, (long long)unit.size()));
  const GridView view = grid.view();
  const float cell = 1.0f / view.inv_cell;
  const std::size_t stride = noise_query_stride(unit.size());
  std::vector<vec3> at((unit.size() + stride - 1) / stride);
  std::vector<float> measured(at.size());
  const NoiseGrids noise(unit, view);
  cpu::parallel_for(std::int64_t(at.size()), [&](std::int64_t q) {
    at[std::size_t(q)] = unit[std::size_t(q) * stride];
    measured[std::size_t(q)] = measured_noise(query_spacing(view, cell, at[std::size_t(q)], k, &noise.views()));
  });
  return RegionalNoise(std::move(at), std::move(measured));
}

}  // namespace

struct SupportSteps::Tree {
  points_detail::CloudAdaptor adaptor;
  points_detail::KdTree tree;
  explicit Tree(std::span<const vec3> unit)
      : adaptor{unit}, tree(3, adaptor, nanoflann::KDTreeSingleIndexAdaptorParams(16)) {
    tree.buildIndex();
  }
};

SupportSteps::SupportSteps(const SampleSet& set)
    : set_(set),
      k_(support_neighbours(set.cloud_size)),
      tree_(std::make_unique<Tree>(set.unit)) {}

SupportSteps::~SupportSteps() = default;

std::size_t SupportSteps::found_in_cloud(std::size_t count) const {
  return std::size_t(std::min<std::uint64_t>(count, set_.cloud_size));
}

bool SupportSteps::within_margin(std::size_t i, float d2) const {
  return set_.margin.empty() || std::sqrt(d2) <= set_.margin[i];
}

bool SupportSteps::row_like(std::size_t i) const { return farthest_[i] > points_detail::kRowGrowth * kth_[i]; }

// For every sample, s_i: the median of d_k over it and its k nearest neighbours, d_k(j) the
// distance from p_j to its k-th nearest other sample. The median, not p_i's own d_k: a stray
// sample far from the rest has a large d_k but takes its neighbours' width, which leaves it
// too few samples to make a surface of its own (no floating blob); and widths vary smoothly,
// so the surface does not pucker where two neighbours' widths differ by chance. Beside it,
// the least d_k of p_i's neighbours over that median (kSparseEvenness). In a cloud sampled in
// rows (rows.hpp) a row's sample takes the distance to the next row for its d_k; the widths
// then widen against the median of the plain d_k, what h was estimated from.
void SupportSteps::measure_spacing(bool rows, Progress* progress) {
  const std::span<const vec3> unit = set_.unit;
  const points_detail::KdTree& tree = tree_->tree;
  const std::size_t n = unit.size();
  const auto k = std::size_t(k_);
  // How many neighbours a query finds when the set holds them all.
  kth_.assign(n, 0.0f), farthest_.assign(n, 0.0f), complete_.assign(n, 0);
  // 2k + 1 below: each query finds its own point at distance 0; the 2k-th nearest tells a
  // row from a surface (rows.hpp).
  points_detail::parallel_for_in_tree_order(tree, [&](std::int64_t s) {
    const auto i = std::size_t(s);
    unsigned index[2 * kSupportNeighbour + 1];
    float d2[2 * kSupportNeighbour + 1];
    const std::size_t found = tree.knnSearch(&unit[i].x, 2 * k + 1, index, d2);
    // A sample of a small cluster, apart from the rest, finds its 15th neighbour beyond the
    // gap: on an even sampling d_15 ≈ 1.4·d_8, so more than 2·d_8 is a gap, not spacing.
    const std::size_t kth = std::min<std::size_t>(k, found - 1);
    const std::size_t eighth = std::min<std::size_t>(8, found - 1);
    kth_[i] = float(std::min(std::sqrt(double(d2[kth])), 2 * std::sqrt(double(d2[eighth]))));
    farthest_[i] = std::sqrt(d2[found - 1]);
    complete_[i] = found == found_in_cloud(2 * k + 1) && within_margin(i, d2[found - 1]);
  }, progress);
  rows_median_ = 0;
  if (rows) {
    const std::vector<float> gaps = points_detail::row_gaps(unit, tree, kth_, farthest_);
    if (!gaps.empty()) {
      rows_median_ = float(double(median_of(kth_)) * set_.scale);
      for (std::size_t i = 0; i < n; ++i) kth_[i] = std::max(kth_[i], gaps[i]);
    }
  }
  spacing_.assign(n, 0.0f), least_.assign(n, 0.0f);
  std::vector<char> complete(n, 0);
  points_detail::parallel_for_in_tree_order(tree, [&](std::int64_t s) {
    const auto i = std::size_t(s);
    unsigned index[kSupportNeighbour + 1];
    float d2[kSupportNeighbour + 1];
    const std::size_t found = points_detail::nearest_by_id(tree, unit[i], k + 1, index, d2, set_.id);
    float d[kSupportNeighbour + 1], least = kInfinity;
    bool held = found == found_in_cloud(k + 1) && within_margin(i, d2[found - 1]);
    for (std::size_t j = 0; j < found; ++j) {
      d[j] = kth_[index[j]];
      held = held && complete_[index[j]];
      if (index[j] != unsigned(i)) least = std::min(least, d[j]);
    }
    std::nth_element(d, d + found / 2, d + found);
    spacing_[i] = float(double(d[found / 2]) * set_.scale);
    least_[i] = d[found / 2] > 0 ? least / d[found / 2] : 1.0f;
    complete[i] = held;
  }, progress);
  complete_ = std::move(complete);
}

void SupportSteps::use_spacing(std::vector<float> spacing, std::vector<float> least) {
  spacing_ = std::move(spacing);
  least_ = std::move(least);
  complete_.assign(set_.unit.size(), 1);
}

// A sample widens where it lies on a sparse surface (support.hpp): sparse, with no denser
// sample among its neighbours, flat, and kSparseNeighbours of its neighbours alike.
void SupportSteps::find_wide(float median_spacing) {
  const std::span<const vec3> unit = set_.unit;
  const points_detail::KdTree& tree = tree_->tree;
  const std::size_t n = unit.size();
  const auto k = std::size_t(k_);
  std::vector<char> sparse(n, 0), sparse_known(complete_);
  points_detail::parallel_for_in_tree_order(tree, [&](std::int64_t s) {
    const auto i = std::size_t(s);
    if (!(kSupportWidening * spacing_[i] > median_spacing && least_[i] >= kSparseEvenness)) return;
    unsigned index[kVolumeNeighbour + 1];
    float d2[kVolumeNeighbour + 1];
    const std::size_t found = points_detail::nearest_by_id(tree, unit[i], kVolumeNeighbour + 1, index, d2, set_.id);
    sparse[i] = !fills_a_volume(unit, std::span<const unsigned>(index, found));
    sparse_known[i] = sparse_known[i] && found == found_in_cloud(kVolumeNeighbour + 1) && within_margin(i, d2[found - 1]);
  });
  wide_.assign(n, 0);
  std::vector<char> complete = sparse_known;
  points_detail::parallel_for_in_tree_order(tree, [&](std::int64_t s) {
    const auto i = std::size_t(s);
    if (!sparse[i]) return;
    unsigned index[kSupportNeighbour + 1];
    float d2[kSupportNeighbour + 1];
    const std::size_t found = points_detail::nearest_by_id(tree, unit[i], k + 1, index, d2, set_.id);
    bool held = sparse_known[i] && found == found_in_cloud(k + 1) && within_margin(i, d2[found - 1]);
    int alike = 0;
    for (std::size_t j = 0; j < found; ++j) {
      alike += index[j] != unsigned(i) && sparse[index[j]];
      held = held && sparse_known[index[j]];
    }
    wide_[i] = alike >= kSparseNeighbours;
    complete[i] = held;
  });
  complete_ = std::move(complete);
}

struct RegionalNoise::Tree {
  points_detail::CloudAdaptor adaptor;
  points_detail::KdTree tree;
  explicit Tree(std::span<const vec3> at) : adaptor{at}, tree(3, adaptor, nanoflann::KDTreeSingleIndexAdaptorParams(16)) {
    tree.buildIndex();
  }
};

RegionalNoise::RegionalNoise(std::vector<vec3> at, std::vector<float> measured)
    : at_(std::move(at)), measured_(measured), tree_(std::make_unique<Tree>(at_)) {
  const points_detail::KdTree& tree = tree_->tree;
  // A query's σ stands where kRegionShare of the queries within the support it asks for
  // (ρ = 2·kNoiseWidths·σ), and at least its kRegionQueries nearest, measured at least half
  // as much.
  std::vector<float> regional(at_.size(), 0.0f);
  cpu::parallel_for(std::int64_t(at_.size()), [&](std::int64_t q) {
    const float sigma = measured[std::size_t(q)];
    if (!(sigma > 0)) return;
    unsigned index[kRegionQueries];
    float d2[kRegionQueries];
    const std::size_t found = tree.knnSearch(&at_[std::size_t(q)].x, kRegionQueries, index, d2);
    const float reach = std::max(float(2 * kNoiseWidths) * sigma, std::sqrt(d2[found - 1]));
    thread_local std::vector<std::pair<unsigned, float>> around;
    around.clear();
    tree.radiusSearch(&at_[std::size_t(q)].x, reach * reach * (1 + 1e-5f), around, nanoflann::SearchParams());
    std::size_t alike = 0;
    for (const auto& other : around) alike += measured[other.first] >= 0.5f * sigma;
    if (double(alike) >= kRegionShare * double(around.size())) regional[std::size_t(q)] = sigma;
  });
  // Each region's σ spreads over the support it asks for, so that the region's edge, whose
  // queries fall short of the share, is widened too.
  spread_ = regional;
  for (std::size_t q = 0; q < at_.size(); ++q) {
    if (!(regional[q] > 0)) continue;
    const float reach = float(2 * kNoiseWidths) * regional[q];
    std::vector<std::pair<unsigned, float>> around;
    tree.radiusSearch(&at_[q].x, reach * reach, around, nanoflann::SearchParams());
    for (const auto& other : around) spread_[other.first] = std::max(spread_[other.first], regional[q]);
  }
}

RegionalNoise::~RegionalNoise() = default;

float RegionalNoise::about(vec3 unit) const {
  unsigned index[kRegionQueries];
  float d2[kRegionQueries];
  const std::size_t found = at_.empty() ? 0 : tree_->tree.knnSearch(&unit.x, kRegionQueries, index, d2);
  float sigma = 0;
  for (std::size_t j = 0; j < found; ++j) sigma = std::max(sigma, spread_[index[j]]);
  return sigma;
}

float RegionalNoise::measured_about(vec3 unit) const {
  unsigned index[kRegionQueries];
  float d2[kRegionQueries];
  const std::size_t found = at_.empty() ? 0 : tree_->tree.knnSearch(&unit.x, kRegionQueries, index, d2);
  float sigma[kRegionQueries];
  for (std::size_t j = 0; j < found; ++j) sigma[j] = measured_[index[j]];
  std::sort(sigma, sigma + found);
  return found > 0 ? sigma[found / 2] : 0.0f;
}

float adaptive_width(float h, float widest, bool wide, float spacing, float median_spacing, float noise, double scale) {
  // Never narrower than h: where the cloud is denser than its median the paper's width stays
  // (a narrower one only shows the scanner's noise and opens holes where dense rows leave
  // gaps); where it is sparser the width grows with the spacing (kSupportWidening), up to
  // `widest`, on a sparse surface; and it is at least kNoiseWidths·σ_i.
  float width = h;
  if (wide) width = std::clamp(kSupportWidening * h * (spacing / median_spacing), h, widest);
  return std::max(width, std::min(widest, float(kNoiseWidths * double(noise) * scale)));
}

namespace {

// The samples of a surface within r of a point on it, over π times their density per area,
// where they scatter by σ along its normal: ∫ φ_σ(z)·(r² − z²) dz over |z| < r.
double held_within(double r, double sigma) {
  if (!(sigma > 0)) return r * r;
  const double a = r / sigma;
  const double within = std::erf(a / std::sqrt(2.0));
  const double density = std::exp(-0.5 * a * a) / std::sqrt(2 * 3.14159265358979323846);
  return r * r * within - sigma * sigma * (within - 2 * a * density);
}

}  // namespace

bool merges_samples(float h, float spacing, float sigma, float kappa) {
  if (!(spacing > 0) || !(sigma > 0)) return false;
  // s_i holds k samples, ρ_i the same density over its wider disc; a noisy slab thicker than
  // s_i packs s_i's k in less of the surface.
  const double held = double(kSupportNeighbour) * held_within(double(kappa) * double(h), double(sigma)) /
                      held_within(double(spacing), double(sigma));
  return held > kSupportSamplesMost;
}

float noise_of_h(float h, float median_spacing) {
  return h > 2 * median_spacing ? float(double(h) / kNoiseWidths) : 0.0f;
}

void take_merged(SupportWidths& widths, std::vector<char> merged) {
  widths.merged_count = std::count(merged.begin(), merged.end(), char(1));
  if (widths.merged_count > 0) widths.merged = std::move(merged);
}

float widest_width(float h, const ProjectionParams& params, double diagonal) {
  return std::max(h, std::min(h * kSupportSpread, float(diagonal * double(h) / double(params.rho))));
}

SupportWidths support_widths(std::span<const vec3> points, const ProjectionParams& params) {
  const float h = params.h;
  if (!(h > 0) || !std::isfinite(h)) throw Error("h must be a positive number (got " + std::to_string(h) + ")");
  SupportWidths out;
  out.least = out.median = out.largest = h;
  out.h.assign(points.size(), h);
  if (params.support == Support::global || points.size() < 2) return out;

  const UnitFrame frame = unit_frame(points);
  const std::vector<vec3> unit = to_unit(points, frame);
  // The noise first: its grid of every point is freed before the steps' tree and arrays are
  // built (at 10^7 points both together set the in-core run's peak, issue 28).
  const RegionalNoise noise = regional_noise(unit, support_neighbours(unit.size()));
  SupportSteps steps(SampleSet{unit, {}, {}, unit.size(), frame.scale});
  {
    Progress progress("support widths", 2 * std::int64_t(unit.size()));
    steps.measure_spacing(true, &progress);
  }
  std::vector<float> spacing(steps.spacing().begin(), steps.spacing().end());
  const float median_d = steps.rows_median() > 0 ? steps.rows_median() : median_of(std::move(spacing));
  if (!(median_d > 0)) return out;  // most samples coincide with k others: no spacing to follow
  const float widest = widest_width(h, params, frame.diagonal);
  steps.find_wide(median_d);
  std::vector<char> merged(unit.size(), 0);
  const float cloud_noise = noise_of_h(h, median_d);
  cpu::parallel_for(std::int64_t(unit.size()), [&](std::int64_t s) {
    const auto i = std::size_t(s);
    out.h[i] = adaptive_width(h, widest, steps.wide(i), steps.spacing()[i], median_d, noise.about(unit[i]), frame.scale);
    const float sigma = std::max(cloud_noise, float(double(noise.measured_about(unit[i])) * frame.scale));
    merged[i] = merges_samples(out.h[i], steps.spacing()[i], sigma, params.rho / params.h);
  });
  take_merged(out, std::move(merged));
  out.least = *std::min_element(out.h.begin(), out.h.end());
  out.largest = *std::max_element(out.h.begin(), out.h.end());
  out.median = median_of(out.h);
  return out;
}

}  // namespace pss
