// A tile's set in a work's request (tile_works.hpp), as the works read it back: the steps'
// shared first part.
#pragma once

#include <cstddef>
#include <vector>

#include "pss/spatial/support_grid.hpp"
#include "pss/spatial/support_layout.hpp"
#include "tile_bytes.hpp"
#include "tile_works.hpp"

namespace pss {

void put_tile(ByteWriter& out, const UnitTile& tile);

struct TileArrays {
  SupportLayout layout;
  std::size_t own;
  std::vector<vec3> unit;
  std::vector<float> h;
  std::vector<int> samples;
  std::vector<vec3> sample_at;
  std::vector<int> into;
  std::vector<vec3> normals;
};

// Throws Error where the arrays do not hold together.
TileArrays get_tile(ByteReader& in);

// The grid of the tile's samples, merged ones at their cubes' means with their masses, with
// their normals where the surface fits them.
SupportGrid grid_of_tile(const TileArrays& t);

// The sorted indices of the grid's samples that are the tile's own (their places in the set
// below `own`), in the grid's order.
std::vector<int> own_sorted_samples(const SupportGrid& grid, std::size_t own);

}  // namespace pss
