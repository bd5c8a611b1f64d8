// A cloud's spacing estimated tile by tile (issue 28): the same estimate as in core
// (points/spacing.hpp), to the last bit, from a cloud on disk that need not fit in memory.
#pragma once

#include <cstddef>

#include "pss/io/tiled_cloud.hpp"
#include "pss/points/spacing.hpp"

namespace pss {

// estimate_spacing of the cloud's positions: the same queries (every stride-th point), each
// answered in its tile and a halo that doubles until it holds the query's k nearest.
SpacingEstimate estimate_spacing(const TiledCloud& cloud, int k = 15, std::size_t max_samples = 20000);

}  // namespace pss
