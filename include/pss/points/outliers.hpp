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

// Where the noise widens the supports, a support on the surface holds hundreds of samples,
// and strays strewn about it, each other's neighbours, a few: more than 3, and a plane through
// so few passes near them, so both tests above let them be (a noisy torus with 1 % of its
// points strewn through its box: 550 strays kept, floating flakes). A sample whose neighbours
// weigh less than this share of the median sample's is set aside too: on an even, clean cloud
// (supports of about 60) the share is under 3 and changes nothing (docs/paper-notes.md).
inline constexpr float kOutlierHeldShare = 1.0f / 32;

// The plane of sorted sample i's neighbours (the samples whose supports hold it, itself left
// out), weighted as the fits weigh them: through their weighted mean, its normal of either
// side; not fitted with fewer than 3 of them. held: their masses added up
// (SupportGridView::mass_of).
struct NeighboursPlane {
  vec3 mean{0.0f}, normal{0.0f};
  float held = 0;
  bool fitted = false;
};
PSS_HOST_DEVICE inline NeighboursPlane neighbours_plane(const SupportGridView& grid, int i) {
  const vec3 p = grid.points[i];
  WeightedMoments m(p);
  NeighboursPlane plane;
  grid.for_each_covering(p, [&](vec3 q, float d2, int j) {
    if (j == i) return;
    m.add(q, grid.mass_of(j) * gaussian_weight(d2, grid.inv_h2[j]));
    plane.held += grid.mass_of(j);
  });
  if (m.count < 3 || !(m.weight_sum > 0)) return plane;
  plane.mean = m.mean();
  plane.normal = smallest_eigenvector(m.covariance_about_mean(), vec3(0.0f)).vector;  // no hint: any side
  plane.fitted = true;
  return plane;
}

// The distance of sorted sample i to its neighbours' plane, over its h_i; infinity with
// fewer than 3 neighbours: alone, or in a cluster too small to be a surface, it still enters
// the fits of points between it and others (a floating flake, a bump). held[i]: the masses
// of its neighbours added up.
struct OutlierDistanceKernel {
  SupportGridView grid;
  float* out;
  float* held;
  PSS_HOST_DEVICE void operator()(std::int64_t k) const {
    const int i = int(k);
    const NeighboursPlane plane = neighbours_plane(grid, i);
    held[i] = plane.held;
    out[i] = plane.fitted ? abs(glm::dot(grid.points[i] - plane.mean, plane.normal)) * sqrt(grid.inv_h2[i]) : kInfinity;
  }
};

struct OutlierReport {
  std::int64_t set_aside = 0;
  float threshold = 0;   // in units of h_i
  float least_held = 0;  // the neighbours' mass a sample needs (kOutlierHeldShare)
};

// Whether a sample with this distance and neighbours' mass (OutlierDistanceKernel) is kept:
// near its neighbours' plane and held by enough of them. In core and tile by tile alike.
inline bool on_the_surface(float distance, float held, const OutlierReport& report) {
  return distance <= report.threshold && held >= report.least_held;
}

// The largest distance a sample on the surface lies at: kOutlierSigmas robust standard
// deviations of the finite distances, and at least kOutlierFloor. With `mass` (one per
// distance: merged samples, points/merged_samples.hpp), the median weighs each by its mass,
// so that the few points of a cube at the noise's edge count as few.
float outlier_threshold(std::span<const float> distance, std::span<const float> mass = {});

// kOutlierHeldShare of the median of the finite `held` (weighed by `mass` where given, as
// above): the neighbours' mass below which a sample is set aside.
float least_held(std::span<const float> held, std::span<const float> mass = {});

// keep[i] for each sorted sample of `grid` (phase "outliers" on `backend`), with
// report.threshold and report.least_held when they are set, else with those of these
// distances and neighbours' masses (set then).
std::vector<char> samples_on_the_surface(const SupportGrid& grid, Backend backend, Stats& stats, OutlierReport& report);

// The range-query grid of `points` with widths h[i] (kappa = ρ/h), the points `merge` marks
// (support.hpp; empty: none) merged (points/merged_samples.hpp) and, with
// OutlierPolicy::set_aside, without the samples set aside (in kOutlierPasses passes, each on
// the grid of the last's samples); its original_index() still counts in `points` (a merged
// sample's is its cube's first point's).
SupportGrid grid_of_samples(std::span<const vec3> points, std::span<const float> h, std::span<const char> merge,
                            float kappa, OutlierPolicy policy, Backend backend, Stats& stats, OutlierReport& report);

}  // namespace pss
