#include "pss/points/outliers.hpp"

#include <algorithm>
#include <bit>
#include <cstdint>
#include <limits>
#include <cmath>
#include <memory>

#include "pss/backend/mirror.hpp"
#include "pss/backend/parallel_for.hpp"
#include "pss/points/merged_samples.hpp"
#include "pss/spatial/grid_mirror.hpp"

namespace pss {

namespace {

struct Measured {
  std::vector<float> distance, held;
};

Measured distances_to_neighbours_planes(const SupportGrid& grid, Backend backend, Stats& stats) {
  const std::size_t n = grid.sorted_points().size();
  const GridMirror g(backend, grid);
  Mirror<float> out(backend, n), held(backend, n);
  Progress progress("outliers", std::int64_t(n));
  parallel_for(backend, "outliers", std::int64_t(n), OutlierDistanceKernel{g.view(), out.data(), held.data()}, stats,
               &progress);
  return {out.take(), held.take()};
}

// The median of the finite values (none negative), each weighing its mass (1 each without
// masses). With masses, without a copy (issue 28: the tiles hold these for every point): the
// least v with the masses of the values up to v at least half the total, found by bisecting
// the floats' bit patterns, which order non-negative floats as their values (31 passes).
float weighted_median(std::span<const float> value, std::span<const float> mass) {
  if (mass.empty()) {
    std::vector<float> finite;
    for (const float v : value)
      if (std::isfinite(v)) finite.push_back(v);
    if (finite.empty()) return 0;
    std::nth_element(finite.begin(), finite.begin() + std::ptrdiff_t(finite.size() / 2), finite.end());
    return finite[finite.size() / 2];
  }
  double total = 0;
  for (std::size_t i = 0; i < value.size(); ++i)
    if (std::isfinite(value[i])) total += mass[i];
  if (!(total > 0)) return 0;
  std::uint32_t lo = 0, hi = std::bit_cast<std::uint32_t>(std::numeric_limits<float>::max());
  while (lo < hi) {
    const std::uint32_t mid = lo + (hi - lo) / 2;
    const float v = std::bit_cast<float>(mid);
    double below = 0;
    for (std::size_t i = 0; i < value.size(); ++i)
      if (std::isfinite(value[i]) && value[i] <= v) below += mass[i];
    if (below >= total / 2)
      hi = mid;
    else
      lo = mid + 1;
  }
  return std::bit_cast<float>(lo);
}

}  // namespace

// The noise's scale, robustly: 1.4826 times the median distance is σ for Gaussian noise.
float outlier_threshold(std::span<const float> distance, std::span<const float> mass) {
  return std::max(kOutlierFloor, kOutlierSigmas * 1.4826f * weighted_median(distance, mass));
}

float least_held(std::span<const float> held, std::span<const float> mass) {
  return kOutlierHeldShare * weighted_median(held, mass);
}

std::vector<char> samples_on_the_surface(const SupportGrid& grid, Backend backend, Stats& stats, OutlierReport& report) {
  const Measured m = distances_to_neighbours_planes(grid, backend, stats);
  if (!(report.threshold > 0)) {
    report.threshold = outlier_threshold(m.distance, grid.masses());
    report.least_held = least_held(m.held, grid.masses());
  }
  std::vector<char> keep(m.distance.size());
  for (std::size_t i = 0; i < keep.size(); ++i)
    keep[i] = on_the_surface(m.distance[i], m.held[i], report);
  return keep;
}

SupportGrid grid_of_samples(std::span<const vec3> points, std::span<const float> h, std::span<const char> merge,
                            float kappa, OutlierPolicy policy, Backend backend, Stats& stats, OutlierReport& report) {
  report = {};
  MergedSamples merged;
  if (!merge.empty()) {
    merged = merge_samples(points, h, merge);
    points = merged.positions;
  }
  // Held by pointer so that the old grid is freed before the next is built (an optional's
  // emplace does the same, but GCC 12 then warns of its vectors as maybe uninitialised).
  auto grid = merge.empty() ? std::make_unique<SupportGrid>(points, h, kappa)
                            : std::make_unique<SupportGrid>(points, h, merged.samples, kappa);
  grid->set_members(merged.into);
  if (policy == OutlierPolicy::keep) return std::move(*grid);
  // Twice: a stray next to another stray fits its plane through it, and stands out once the
  // other is gone. The second pass keeps the first's threshold.
  for (int pass = 0; pass < kOutlierPasses; ++pass) {
    const std::vector<char> keep = samples_on_the_surface(*grid, backend, stats, report);
    const std::span<const int> original = grid->original_index();
    const auto kept = std::size_t(std::count(keep.begin(), keep.end(), char(1)));
    if (kept == keep.size()) break;
    std::vector<int> input_index;  // the kept, in the cloud's order: ties within a cell go by it, as in tiles
    input_index.reserve(kept);
    for (std::size_t k = 0; k < keep.size(); ++k)
      if (keep[k]) input_index.push_back(original[k]);
    std::sort(input_index.begin(), input_index.end());
    report.set_aside += std::int64_t(keep.size() - kept);
    grid.reset();  // before the next is built: two grids at once were the phase's peak (issue 28)
    grid = std::make_unique<SupportGrid>(points, h, input_index, kappa);
    grid->set_members(merged.into);
  }
  return std::move(*grid);
}

}  // namespace pss
