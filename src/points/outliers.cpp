#include "pss/points/outliers.hpp"

#include <algorithm>
#include <cmath>
#include <memory>

#include "pss/backend/mirror.hpp"
#include "pss/backend/parallel_for.hpp"
#include "pss/points/merged_samples.hpp"
#include "pss/spatial/grid_mirror.hpp"

namespace pss {

namespace {

std::vector<float> distances_to_neighbours_planes(const SupportGrid& grid, Backend backend, Stats& stats) {
  const std::size_t n = grid.sorted_points().size();
  const GridMirror g(backend, grid);
  Mirror<float> out(backend, n);
  Progress progress("outliers", std::int64_t(n));
  parallel_for(backend, "outliers", std::int64_t(n), OutlierDistanceKernel{g.view(), out.data()}, stats, &progress);
  return out.take();
}

}  // namespace

// The noise's scale, robustly: 1.4826 times the median distance is σ for Gaussian noise.
float outlier_threshold(std::vector<float> distance, std::span<const float> mass) {
  if (mass.empty()) {
    std::erase_if(distance, [](float d) { return !std::isfinite(d); });
    if (distance.empty()) return kOutlierFloor;
    std::nth_element(distance.begin(), distance.begin() + distance.size() / 2, distance.end());
    return std::max(kOutlierFloor, kOutlierSigmas * 1.4826f * distance[distance.size() / 2]);
  }
  std::vector<std::pair<float, float>> weighed;  // (distance, mass)
  double total = 0;
  for (std::size_t i = 0; i < distance.size(); ++i)
    if (std::isfinite(distance[i])) {
      weighed.emplace_back(distance[i], mass[i]);
      total += mass[i];
    }
  std::sort(weighed.begin(), weighed.end());
  double below = 0;
  for (const auto& [d, m] : weighed)
    if ((below += m) >= total / 2) return std::max(kOutlierFloor, kOutlierSigmas * 1.4826f * d);
  return kOutlierFloor;
}

std::vector<char> samples_on_the_surface(const SupportGrid& grid, Backend backend, Stats& stats, OutlierReport& report) {
  const std::vector<float> distance = distances_to_neighbours_planes(grid, backend, stats);
  if (!(report.threshold > 0)) report.threshold = outlier_threshold(distance, grid.masses());
  std::vector<char> keep(distance.size());
  for (std::size_t i = 0; i < keep.size(); ++i) keep[i] = distance[i] <= report.threshold;
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
    std::vector<int> input_index;  // the kept, in the old grid's order: ties go as they went
    input_index.reserve(kept);
    for (std::size_t k = 0; k < keep.size(); ++k)
      if (keep[k]) input_index.push_back(original[k]);
    report.set_aside += std::int64_t(keep.size() - kept);
    grid.reset();  // before the next is built: two grids at once were the phase's peak (issue 28)
    grid = std::make_unique<SupportGrid>(points, h, input_index, kappa);
    grid->set_members(merged.into);
  }
  return std::move(*grid);
}

}  // namespace pss
