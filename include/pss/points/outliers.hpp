// Setting aside the samples that are not on the surface the others define (issue 26): a
// stray near a surface dominates the weights at the points around it, so that any fit there,
// RIMLS's robust one included, bends to it and shows a floating flake. Each sample is
// measured against the plane of its neighbours without it (Eq. 1's WLS plane at p_i over
// N(p_i) \ {p_i}): its distance to that plane, in units of its own h_i. A sample farther
// than the cloud's noise allows (kOutlierSigmas robust standard deviations of those
// distances, and at least kOutlierFloor·h_i, what a crease or a thin part gives on clean
// data), or with fewer than 3 others in reach, is set aside: not a sample of the surface.
// It is still a point: `pss project` projects it onto the surface of the others, or leaves
// it where it is with too few neighbours.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "pss/backend/backend.hpp"
#include "pss/core/stats.hpp"
#include "pss/fit/inverse_power.hpp"
#include "pss/fit/moments.hpp"
#include "pss/fit/weights.hpp"
#include "pss/points/projection.hpp"
#include "pss/spatial/support_grid.hpp"

namespace pss {

// A 90° crease's samples lie up to ~0.2h off the plane fitted across it, a thin part's up to
// its half thickness; a stray that makes a flake lies ~h and more off (docs/paper-notes.md).
inline constexpr float kOutlierFloor = 0.5f;
inline constexpr float kOutlierSigmas = 4.0f;
inline constexpr int kOutlierPasses = 2;  // grid_of_samples

// The distance of sorted sample i to its neighbours' plane, over its h_i; infinity with
// fewer than 3 neighbours: alone, or in a cluster too small to be a surface, it still enters
// the fits of points between it and others (a floating flake, a bump).
struct OutlierDistanceKernel {
  SupportGridView grid;
  float* out;
  PSS_HOST_DEVICE void operator()(std::int64_t k) const {
    const int i = int(k);
    const vec3 p = grid.points[i];
    WeightedMoments m(p);
    grid.for_each_covering(p, [&](vec3 q, float d2, int j) {
      if (j != i) m.add(q, grid.mass_of(j) * gaussian_weight(d2, grid.inv_h2[j]));
    });
    if (m.count < 3 || !(m.weight_sum > 0)) {
      out[i] = kInfinity;
      return;
    }
    const vec3 n = smallest_eigenvector(m.covariance_about_mean(), vec3(0.0f)).vector;  // no hint: any side
    out[i] = abs(glm::dot(p - m.mean(), n)) * sqrt(grid.inv_h2[i]);
  }
};

struct OutlierReport {
  std::int64_t set_aside = 0;
  float threshold = 0;  // in units of h_i
};

// The largest distance a sample on the surface lies at: kOutlierSigmas robust standard
// deviations of the finite distances, and at least kOutlierFloor. With `mass` (one per
// distance: merged samples, points/merged_samples.hpp), the median weighs each by its mass,
// so that the few points of a cube at the noise's edge count as few.
float outlier_threshold(std::vector<float> distance, std::span<const float> mass = {});

// keep[i] for each sorted sample of `grid` (phase "outliers" on `backend`), with
// report.threshold when it is set, else with the threshold of these distances (set then).
std::vector<char> samples_on_the_surface(const SupportGrid& grid, Backend backend, Stats& stats, OutlierReport& report);

// The range-query grid of `points` with widths h[i] (kappa = ρ/h), the points `merge` marks
// (support.hpp; empty: none) merged (points/merged_samples.hpp) and, with
// OutlierPolicy::set_aside, without the samples set aside (in kOutlierPasses passes, each on
// the grid of the last's samples); its original_index() still counts in `points` (a merged
// sample's is its cube's first point's).
SupportGrid grid_of_samples(std::span<const vec3> points, std::span<const float> h, std::span<const char> merge,
                            float kappa, OutlierPolicy policy, Backend backend, Stats& stats, OutlierReport& report);

}  // namespace pss
