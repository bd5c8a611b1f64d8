// How far a cloud's samples scatter about the surface they sample (issue 26). Where that
// noise is comparable to the spacing, a width h set by the spacing alone leaves the PSS
// ragged: Eq. 1's energy then has several minima along the normal, projections stop
// unconverged and a mesh falls into bubbles (a 200,000-point torus with noise 0.8 h meshed
// into 612 parts; with h raised to 2.5 times the noise, into one watertight part).
#pragma once

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
// residuals' lower quartile is over kSheetsQuartile of their median: Gaussian noise gives
// 0.47, two clean sheets (a thin part, its faces both in reach) fitted by one surface ~1.
double query_noise(const GridView& view, vec3 c, float reach);

inline constexpr int kNoiseFit = 12;
inline constexpr double kSheetsQuartile = 0.8;

// The noise of a query whose k-th nearest neighbour lies at `kth`: query_noise at a reach of
// kth (the nearest samples, so that a thin part's other face, beyond the spacing, stays out),
// widened to kNoiseReach·σ while σ asks for it (a slab of noise cut by a ball narrower than
// ~3σ looks thinner than it is), at most kNoiseReachGrowth times.
struct QueryNoise {
  double sigma;  // NaN where query_noise gives it
  double reach;  // the last reach asked: the farthest any neighbour used lies
};
QueryNoise noise_near(const GridView& view, vec3 c, double kth);

inline constexpr double kNoiseReach = 6.0;
inline constexpr int kNoiseReachGrowth = 3;

}  // namespace pss
