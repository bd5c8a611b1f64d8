// How far a cloud's samples scatter about the surface they sample (issue 26). Where that
// noise is comparable to the spacing, a width h set by the spacing alone leaves the PSS
// ragged: Eq. 1's energy then has several minima along the normal, projections stop
// unconverged and a mesh falls into bubbles (a 200,000-point torus with noise 0.65 h meshed
// into 610 parts; with h raised to 2.2 times the noise or more, into one watertight part).
#pragma once

#include <cmath>

#include "pss/core/types.hpp"

namespace pss {

struct GridView;

// A query's noise: σ of its neighbours (within `reach`, in the grid's frame) about the
// quadric height field z = ax² + bxy + cy² + dx + ey + f fitted to them by least squares
// over their principal plane. The quadric takes the surface's curvature, so a clean curved
// surface gives ~0 (to third order in the reach), and Gaussian noise gives its σ: 1.4826
// times the median absolute residual, corrected for the six fitted coefficients. Robust to
// a crease or a stray among the neighbours. NaN with too few neighbours to fit (kNoiseFit),
// where they lie along a line (a cloud of rows: no surface at this reach), or where the
// residuals' lower quartile is over sheets_quartile of their median: Gaussian residuals give
// 0.47 (over 0.5 + 1.2/√N in 3 % of fits of N, by simulation), two sheets fitted by one
// surface more (0.68–0.85 for two noisy sheets in reach, both faces of a thin part).
double query_noise(const GridView& view, vec3 c, float reach);

inline constexpr int kNoiseFit = 12;
inline double sheets_quartile(double fitted) { return 0.5 + 1.2 / std::sqrt(fitted); }

// The noise of a query whose k-th nearest neighbour lies at `kth`: query_noise at a reach of
// kth (the nearest samples, so that a thin part's other face, beyond the spacing, stays out),
// widened to kNoiseReach·σ while σ asks for it (a slab of noise cut by a ball narrower than
// ~4σ looks thinner than it is: 0.58σ at 2σ, 0.89σ at 4σ, 0.92–0.97σ at 6σ), up to
// kNoiseReachMost·kth. NaN where a reach gives NaN (a thin part's faces come into a wider
// ball: not noise), or where the last reach is still short of kNoiseReach·σ: points that
// fill every ball (a volume, trees in a LiDAR tile: σ ~ a third of any reach) are no slab
// about a surface, and neither is noise too thick to see across within the farthest reach
// (measured to σ ≈ 1.4 kth on noisy tori, lost by 1.9 kth).
struct QueryNoise {
  double sigma;
  double reach;  // the last reach asked: the farthest any neighbour used lies
};
QueryNoise noise_near(const GridView& view, vec3 c, double kth);

inline constexpr double kNoiseReach = 6.0;
inline constexpr double kNoiseReachMost = 6.0;

}  // namespace pss
