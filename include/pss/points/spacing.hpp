// How densely a cloud is sampled, and the h that follows from it.
#pragma once

#include <cstddef>
#include <span>
#include <vector>

#include "pss/core/types.hpp"

namespace pss {

struct SpacingEstimate {
  double mean_nearest = 0;  // mean distance to the nearest other sample
  double median_kth = 0;    // median distance to the k-th nearest sample
  // Its spread: the least and the largest, over the same samples. A cloud whose spacing
  // varies (a scan's near and far parts, a locally refined mesh) shows it here.
  double min_kth = 0, max_kth = 0;
  int k = 0;
  // The samples' scatter about their surface (points/noise.hpp): the median σ over the
  // queries, 0 where none could fit one.
  double noise = 0;
  // h = median_kth with k = 15: a ball of radius ρ = 2h on a surface then holds about
  // 4·k = 60 samples, ~20 of them with weight above e⁻¹: enough to average noise down to
  // about a third (tests/projection_test.cpp) with a curvature bias of order κ³h⁴. Where the
  // noise asks for more, kNoiseWidths·noise (docs/paper-notes.md, issue 26).
  double suggested_h = 0;
};

// Uses at most `max_samples` query points (evenly strided) so that huge clouds stay fast.
// Throws Error for fewer than two points.
SpacingEstimate estimate_spacing(std::span<const vec3> points, int k = 15, std::size_t max_samples = 20000);

// The parts of estimate_spacing, for a cloud read tile by tile (tiles/spacing.hpp):
// every stride-th point is a query (spacing_stride);
std::size_t spacing_stride(std::size_t points, std::size_t max_samples);
// a query's distances to its nearest and k-th nearest other points, in a grid of points in
// the cloud's unit frame with cells of `cell` (exact wherever the grid holds every point
// within the k-th distance of c), and with `noise` (the same points' NoiseGrids) its noise;
struct QuerySpacing {
  double nearest, kth;
  double noise;  // noise_near at that k-th distance (points/noise.hpp), or NaN
  double reach;  // the farthest a point it used lies: exact wherever the grid holds that
};
struct GridView;
struct NoiseViews;
QuerySpacing query_spacing(const GridView& view, float cell, vec3 c, int k, const NoiseViews* noise);
// the noise measured at every noise_query_stride-th query only: at most ~kNoiseQueries of
// them, plenty for a median, since a noisy cloud's wider reach costs more per query;
inline constexpr std::size_t kNoiseQueries = 5000;
std::size_t noise_query_stride(std::size_t queries);
// and the estimate from the queries' results, in query order, scaled back by the unit
// frame's `scale`.
SpacingEstimate spacing_of(const std::vector<QuerySpacing>& queries, int k, double scale);

// h is at least this many times the noise: on a noisy torus the mesh held together from
// h ≈ 2σ (docs/paper-notes.md).
inline constexpr double kNoiseWidths = 3.0;

// The h a renderer uses when none is given: the suggested h, or 1 for fewer than two samples
// (a single sample has no spacing, and no surface whatever h is: fewer than three neighbours).
// Throws Error where estimate_spacing does for two or more (all samples coincide).
float default_h(std::span<const vec3> points);

}  // namespace pss
