// Whether a cloud is worked on in core or tile by tile within a memory budget (issue 28:
// `--memory`), and how many points a tile holds.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>

#include "pss/core/error.hpp"

namespace pss {

// What tiles do not do (yet), where a cloud's work is done in core only.
struct NotTiled : Error {
  using Error::Error;
};

// What a command holds, in bytes a point: in core (everything at once, measured), beside
// the tiles (per-point results kept for the whole cloud), and for each point of a tile or
// its halo while the tile is worked on.
struct MemoryCosts {
  std::uint64_t in_core = 0, held = 0, tile = 0;
};

struct MemoryPlan {
  std::uint64_t budget = 0;  // bytes
  std::uint64_t points = 0;  // the file's count, or at most that (a text file's lines)
  bool tiled = false;
  std::uint64_t points_per_tile = 0;  // when tiled
  std::size_t buffer_bytes = 0;       // the tiles' store's, when tiled
};

// The budget when none is given: half the memory this process may take
// (physical_memory_bytes), or 4 GiB where that is unknown.
std::uint64_t default_memory_budget();

// The folder of the tiles' scratch files: $TMPDIR, else /tmp (temp_directory_path). Throws
// Error naming it where it is no folder.
std::filesystem::path scratch_folder();

// The point count a file declares (PLY, LAS), or for a text file its number of lines.
std::uint64_t point_count_at_most(const std::filesystem::path& file);

// In core where `costs.in_core` a point fits the budget; else tiles as large as the budget
// allows, with a halo taken as large as the tile. Throws Error (naming --memory) where the
// budget cannot hold even the per-point results and a tile of a few thousand points.
MemoryPlan plan_memory(const std::filesystem::path& file, std::uint64_t budget, const MemoryCosts& costs);

// A plan in core made tiles for `ranks` processes to share (tiles/farm.hpp): about four a
// rank, of a few thousand points at least. Unchanged where it is tiled already, or where the
// cloud is too small to share.
MemoryPlan spread_over_ranks(MemoryPlan plan, int ranks);

}  // namespace pss
