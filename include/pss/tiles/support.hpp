// The adaptive widths tile by tile (issue 28): support.hpp's h_i, to the last bit, from a
// cloud on disk that need not fit in memory.
#pragma once

#include "pss/core/error.hpp"
#include "pss/tiles/memory_plan.hpp"
#include "pss/io/tiled_cloud.hpp"
#include "pss/points/projection.hpp"
#include "pss/points/support.hpp"
#include "pss/tiles/farm.hpp"

namespace pss {

// support_widths of the cloud's positions. Two passes over the tiles, each tile with a halo
// that doubles until it holds every neighbour its own samples' answers read
// (points/support_steps.hpp): the first finds each sample's spacing and the noise at the
// noise queries, the second, from their medians and regions, which samples widen and each
// width. Holds 12 bytes a point (the spacings, their least neighbours' and the widths) beside
// one tile at a time. Throws Error for a width that is not a positive number, and
// NotTiled (tiles/memory_plan.hpp) for a cloud sampled in rows (rows.hpp: the rows' chains span the cloud;
// support_widths of the points in core serves).
// Each pass's tiles may be spread over processes (tiles/farm.hpp).
SupportWidths support_widths(const TiledCloud& cloud, const ProjectionParams& params, TileFarm& farm = local_farm());

}  // namespace pss
