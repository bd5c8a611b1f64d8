// Clouds sampled in rows (issue 26): slices of a CAD part or a CT stack, a profile scanner's
// lines. blade.off holds rows 1.87 apart, each sampled every 0.17: a sample's 15 nearest
// neighbours all lie on its own row, so the width they give (0.77) never reaches the next
// row and the surface shows as a ladder of stripes (83 % of its pixels missing). Where most
// of a cloud lies on such rows, a row's sample takes the distance to the next row as its
// spacing instead (support.cpp), and its width then spans the gap.
#pragma once

#include <span>
#include <vector>

#include "kd_tree.hpp"

namespace pss::points_detail {

// A sample is on a row when its neighbours grow along a curve (its 30th nearest more than
// kRowGrowth times as far as its 15th: on a surface about √2, on a curve 2) and its chain
// (the samples linked to it through each one's 4 nearest) holds at least kRowLength.
inline constexpr float kRowGrowth = 1.7f;
inline constexpr int kRowLength = 30;

// Where at least half of the samples lie on rows: for each of those, the distance to the
// nearest sample of another chain (the next row), or 0 where none lies within the 512
// nearest; for every other sample 0. Empty where the cloud is not sampled in rows. `unit`
// and `tree` as support.cpp's; `kth` and `wide` each sample's spacing there (its 15th
// nearest, at most twice its 8th) and its distance to its 30th nearest. A gap nearer than
// the spacing changes nothing: support.cpp takes the larger.
std::vector<float> row_gaps(std::span<const vec3> unit, const KdTree& tree, std::span<const float> kth,
                            std::span<const float> wide);

}  // namespace pss::points_detail
