// The orientation of normals tile by tile (points/orient_normals.hpp, tiles/orient.hpp): each
// tile's records with those of its halo, every point linked to those within their ρ_j; each
// piece a sign that the tiles agree on where their halos overlap. `pss project` orients the
// projections' normals so, or, for APSS and RIMLS, the samples' (tiles/project.hpp).
#pragma once

#include <cstddef>
#include <filesystem>
#include <memory>
#include <span>
#include <vector>

#include "pss/io/bucket_file.hpp"
#include "pss/io/tiled_cloud.hpp"
#include "pss/points/unit_frame.hpp"
#include "pss/tiles/farm.hpp"
#include "pss/tiles/orient.hpp"
#include "tile_records.hpp"

namespace pss {

struct OrientationInputs {
  const TiledCloud& cloud;
  const UnitFrame& frame;
  const BucketFile& records;      // Projected, a bucket a tile: its own points'
  std::span<const double> moved;  // per tile, the farthest its records lie from its points (unit)
  double reach = 0;               // the widest ρ_j (unit)
  bool merged = false;            // whether samples were merged (a point may follow its sample)
};

struct OrientedInTiles {
  std::unique_ptr<BucketFile> ordered;  // Oriented, a bucket a window: each own record and halo votes
  std::unique_ptr<BucketFile> by_tile;  // Oriented, each tile's own records; empty unless asked
  PieceTurns pieces;                    // per piece, whether it turns
  std::vector<char> seam;  // empty, or per point of the cloud: the seams' turn (or the rays', of a file's) turns it
  bool turned(const Oriented& r) const {
    return pieces(r.piece, r.seen_turned) != (!seam.empty() && seam[r.index] != 0);
  }
};

// The records oriented, in windows of `window_points` (and by tile, where `by_tile`), in
// scratch files in `folder` buffered in at most `buffer_bytes`; `label` names the progress.
OrientedInTiles orient_in_tiles(const OrientationInputs& in, std::size_t window_points, bool by_tile,
                                const std::filesystem::path& folder, std::size_t buffer_bytes, TileFarm& farm,
                                const char* label);

}  // namespace pss
