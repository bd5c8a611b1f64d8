// How far a cloud's samples scatter about the surface they sample (issue 26). Where that
// noise is comparable to the spacing, a width h set by the spacing alone leaves the PSS
// ragged: Eq. 1's energy then has several minima along the normal, projections stop
// unconverged and a mesh falls into bubbles (a 200,000-point torus with noise 0.65 h meshed
// into 610 parts; with h raised to 2.2 times the noise or more, into one watertight part).
#pragma once

#include <cmath>
#include <cstddef>
#include <span>
#include <vector>

#include "pss/core/types.hpp"
#include "pss/spatial/uniform_grid.hpp"

namespace pss {

// A query's noise: σ of its neighbours (within `reach`, in the grid's frame, and within
// `lateral` of the axis along their principal plane's normal: a cylinder, where the reach is
// the wider) about the quadric height field z = ax² + bxy + cy² + dx + ey + f fitted to them
// by least squares over that plane, measured as the distance to it where the fit holds
// enough samples to know its slope. The quadric takes the surface's curvature, so a clean
// curved surface gives ~0 (to third order in the lateral reach), and Gaussian noise gives
// its σ: 1.4826 times the median absolute residual, corrected for the six fitted
// coefficients. Robust to a crease or a stray among the neighbours. NaN with too few
// neighbours to fit (kNoiseFit), where they lie along a line (a cloud of rows: no surface at
// this reach), or where the residuals' lower quartile is over sheets_quartile of their
// median: Gaussian residuals give 0.47 (over 0.5 + 1.2/√N in 3 % of fits of N, by
// simulation), two sheets fitted by one surface more (0.68–0.85 for two noisy sheets in
// reach, both faces of a thin part).
struct NoiseAtReach {
  double sigma;
  std::size_t points;  // the neighbours fitted (none where σ is NaN)
};
NoiseAtReach query_noise(const GridView& view, vec3 c, float reach, float lateral);

inline constexpr int kNoiseFit = 12;
inline double sheets_quartile(double fitted) { return 0.5 + 1.2 / std::sqrt(fitted); }

// The grids the noise reads. A farther reach is asked only where σ asks for it, but there it
// may hold many samples (~200,000 in a volume at 24 k-th distances), and a fit needs a few
// hundred: level L holds the samples whose hash of position falls below 8⁻ᴸ of its range
// (level 0 all of them). Each sample chooses alone, so that a tile and its
// halo hold the same of them as the whole cloud (tiles/spacing.hpp).
inline constexpr int kNoiseLevels = 3;
struct NoiseViews {
  GridView level[kNoiseLevels];
};
class NoiseGrids {
 public:
  // `all`: a grid of `points`, which it keeps as level 0.
  NoiseGrids(std::span<const vec3> points, const GridView& all);
  const NoiseViews& views() const { return views_; }

 private:
  std::vector<UniformGrid> thinned_;
  NoiseViews views_;
};
// Whether a sample of that position is in level L's share.
bool in_noise_level(vec3 p, int level);

// The noise of a query whose k-th nearest neighbour lies at `kth`: query_noise at a reach of
// kth (the nearest samples, so that a thin part's other face, beyond the spacing, stays out),
// widened to kNoiseReach·σ while σ asks for it (a slab of noise cut by a ball narrower than
// ~4σ looks thinner than it is: 0.58σ at 2σ, 0.89σ at 4σ, 0.92–0.97σ at 6σ), up to
// kNoiseReachMost·kth, each reach read at the coarsest level that still fits
// kNoiseFitLeast samples. Laterally the fit reaches the larger of kNoiseLateral·kth and
// kNoiseLateralShare of the reach: a cylinder across the slab. NaN where a reach gives NaN
// (a thin part's faces come into a wider ball: not noise), or where the last reach is still short of
// kNoiseReach·σ: points that fill every ball (a volume, trees in a LiDAR tile: σ ~ a third
// of any reach) are no slab about a surface, and neither is noise too thick to see across
// within the farthest reach.
struct QueryNoise {
  double sigma;
  double reach;  // the last reach asked: the farthest any neighbour used lies
};
QueryNoise noise_near(const NoiseViews& views, vec3 c, double kth);

inline constexpr double kNoiseReach = 6.0;
// A ball of 6 k-th distances read noise over 1.5 kth short (0.89σ at 2 kth, 0.54σ at 5 kth:
// a sphere of σ = 2 kth rendered in flakes); 12 read 0.97σ at 2 kth, 24 0.98σ. But a curved
// surface's terms beyond the quadric read as noise where the reach nears its radius, and
// feed the reach (a torus's tube of radius 6 kth with σ = 1.1 kth read 1.13σ in balls up to
// 24 kth): so the fit reaches less far along the surface than across it, and the walk
// through a volume's wide ball reads a share of it.
inline constexpr double kNoiseLateral = 4.0, kNoiseLateralShare = 0.5;
inline constexpr double kNoiseReachMost = 24.0;
inline constexpr double kNoiseFitLeast = 512;

}  // namespace pss
