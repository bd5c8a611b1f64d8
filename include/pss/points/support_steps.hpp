// The adaptive widths (support.hpp) worked out over one set of samples: the whole cloud in
// core, or a tile and its halo (tiles/support.hpp, issue 28). Each step's answer at a sample
// reads its neighbours, and theirs; where the set may lack one (near a halo's edge) the answer
// is marked incomplete, and a tile is loaded again with a wider halo. Neighbours at equal
// distances are taken in the order of their index in the cloud, so that every set holding a
// sample's neighbours gives it the same answer, to the last bit.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "pss/core/progress.hpp"
#include "pss/core/types.hpp"
#include "pss/points/projection.hpp"
#include "pss/points/spacing.hpp"
#include "pss/points/support.hpp"

namespace pss {

struct SampleSet {
  std::span<const vec3> unit;              // in the cloud's unit frame (unit_frame.hpp)
  std::span<const std::uint64_t> id;       // each sample's index in the cloud; empty: its index here
  std::span<const float> margin;           // the set holds every sample within margin[i] of i; empty: the whole cloud
  std::uint64_t cloud_size = 0;
  double scale = 1;                        // the unit frame's
};

// kSupportNeighbour, or fewer in a cloud of fewer samples.
inline int support_neighbours(std::uint64_t cloud_size) {
  return int(std::min<std::uint64_t>(kSupportNeighbour, cloud_size - 1));
}

class SupportSteps {
 public:
  explicit SupportSteps(const SampleSet& set);
  ~SupportSteps();
  SupportSteps(const SupportSteps&) = delete;
  SupportSteps& operator=(const SupportSteps&) = delete;

  int k() const { return k_; }  // support_neighbours of the cloud

  // s_i and the least d_k among p_i's neighbours over s_i (support.hpp), for every sample;
  // with `rows` (in core only), a cloud sampled in rows takes each row's gap (rows.hpp).
  void measure_spacing(bool rows, Progress* progress = nullptr);
  // Or s_i and least_i as an earlier pass found them, one per sample of the set (tiles/support.hpp).
  void use_spacing(std::vector<float> spacing, std::vector<float> least);
  std::span<const float> spacing() const { return spacing_; }  // s_i, in the input's units
  std::span<const float> least() const { return least_; }
  float rows_median() const { return rows_median_; }          // in a cloud of rows, the plain d_k's median; else 0
  // Whether p_i's d_k grows along a curve (rows.hpp's first test).
  bool row_like(std::size_t i) const;

  // Which samples lie on a sparse surface and widen (support.hpp), given the median spacing.
  void find_wide(float median_spacing);
  bool wide(std::size_t i) const { return wide_[i] != 0; }

  // Whether every answer so far at sample i read only samples of the set.
  bool complete(std::size_t i) const { return complete_[i] != 0; }

 private:
  // How many neighbours a query for `count` finds where the set holds them all.
  std::size_t found_in_cloud(std::size_t count) const;
  // Whether the set holds every sample within √d2 of sample i.
  bool within_margin(std::size_t i, float d2) const;

  struct Tree;
  SampleSet set_;
  int k_ = 0;
  std::unique_ptr<Tree> tree_;
  std::vector<float> kth_, farthest_;  // d_k (at most 2·d_8) and the distance to the 2k-th, unit frame
  std::vector<float> spacing_, least_;
  std::vector<char> complete_, wide_;
  float rows_median_ = 0;
};

// The noise σ_i about each sample (support.hpp, kRegionQueries) from σ measured at the noise
// queries (every noise_query_stride-th sample), in the unit frame; 0 where a query measured none.
class RegionalNoise {
 public:
  RegionalNoise(std::vector<vec3> at, std::vector<float> measured);
  ~RegionalNoise();
  float about(vec3 unit) const;
  // The median σ the kRegionQueries queries nearest `unit` measured, regions or not: whether
  // the samples there scatter (merges_samples), where about() may leave a noisy cloud's
  // widths to its global h.
  float measured_about(vec3 unit) const;

 private:
  struct Tree;
  std::vector<vec3> at_;
  std::vector<float> measured_;
  std::vector<float> spread_;
  std::unique_ptr<Tree> tree_;
};

// A noise query's σ in the unit frame (spacing.hpp's query_spacing), 0 where it measured none.
inline float measured_noise(const QuerySpacing& query) {
  return std::isfinite(query.noise) ? float(query.noise) : 0.0f;
}

// The widest h_i: kSupportSpread·h, and ρ_i within the cloud's bounding-box diagonal.
float widest_width(float h, const ProjectionParams& params, double diagonal);

// h_i (support.hpp) from the steps' answers: `spacing` and `median_spacing` in the input's
// units, `noise` in the unit frame.
float adaptive_width(float h, float widest, bool wide, float spacing, float median_spacing, float noise, double scale);

// Sets widths.merged to `merged` and counts it, or leaves it empty where no point is marked.
void take_merged(SupportWidths& widths, std::vector<char> merged);

}  // namespace pss
