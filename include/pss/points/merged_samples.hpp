// Fewer samples where the noise widens the supports (issue 26): a support of width
// h_i = kNoiseWidths·σ_i holds thousands of samples where σ is a few spacings, and every fit's
// time grows with them while its error falls only as their square root. Where a support would
// hold more than kSupportSamplesMost (support.hpp), the samples in each cube of a lattice of
// side h_i/2 to h_i become one, at their mean, weighing as many as it stands for
// (SupportGridView::mass): a fit's sums over them are the sums over all of them but for the
// spread within the cubes, small against h_i, so the surface stays where all of them put it.
// Its file normal and colour are its points' means (SupportGrid::members).
// On a 300,000-point torus with noise 0.03 R `pss project`'s points lie 0.00402 R (rms) from
// the true torus against 0.00427 R with every sample, and it takes 28.7 s against 75.7 s
// (`pss render` 6.6 s against 38.7 s); a random share of the samples instead made the surface
// visibly bumpier (bench/merged_samples.py, docs/paper-notes.md).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "pss/core/types.hpp"

namespace pss {

// The lattice's side: the power of two at or below this many h_i, in the positions' units, so
// that samples of nearby widths share cubes, and tiles and ranks, which see the same positions
// and widths, the same cubes. With cubes of h_i/4 to h_i/2 the 300,000-point torus's
// projection took 25 s, with h_i/2 to h_i 7 s (the smaller left several hundred merged samples
// in a support, over the 128 a neighbourhood holds), the two as close to the truth (merging
// where a support held over 400).
inline constexpr float kMergeCell = 1.0f;

struct MergedSamples {
  // The points, each cube's first (by index) moved to its cube's mean: what the grid is built of.
  std::vector<vec3> positions;
  std::vector<int> samples;  // the cubes' first points and the points not merged, ascending
  std::vector<int> into;     // per point: its cube's first point, or itself (SupportGrid::set_members)
};

// Merges the points that `merge` marks (support.hpp, SupportWidths::merged), each in its cube
// of side 2^⌊log2(kMergeCell·h_i)⌋ (cubes of different sides apart). The means are summed in
// doubles in the order of the points' indices.
MergedSamples merge_samples(std::span<const vec3> points, std::span<const float> h, std::span<const char> merge);

}  // namespace pss
