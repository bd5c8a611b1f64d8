#include "pss/tiles/memory_plan.hpp"

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <vector>

#include "pss/core/error.hpp"
#include "pss/core/memory.hpp"
#include "pss/core/text.hpp"
#include "pss/io/point_stream.hpp"

namespace pss {

namespace {

// Fewer points a tile and its halo cost more in halo than they hold.
constexpr std::uint64_t kLeastTilePoints = 4096;

}  // namespace

std::uint64_t default_memory_budget() {
  const std::int64_t memory = physical_memory_bytes();
  return memory > 0 ? std::uint64_t(memory) / 2 : std::uint64_t(4) << 30;
}

std::filesystem::path scratch_folder() {
  const char* named = std::getenv("TMPDIR");
  // An empty TMPDIR reads as unset (POSIX), where temp_directory_path would take "".
  const bool empty = named && *named == '\0';
  std::error_code error;
  const std::filesystem::path folder = empty ? std::filesystem::path("/tmp") : std::filesystem::temp_directory_path(error);
  if (error || !std::filesystem::is_directory(folder, error))
    throw Error("the temporary folder " + quote(named && !empty ? named : "/tmp") + " for the tiles is no folder" +
                (error ? ": " + error.message() : std::string()));
  return folder;
}

std::uint64_t point_count_at_most(const std::filesystem::path& file) {
  if (const std::uint64_t declared = open_point_stream(file)->declared_count(); declared > 0) return declared;
  std::ifstream in(file, std::ios::binary);
  if (!in) throw file_error(file, "cannot be opened");
  std::vector<char> block(std::size_t(1) << 20);
  std::uint64_t lines = 0;
  char last = '\n';
  while (in.read(block.data(), std::streamsize(block.size())) || in.gcount() > 0) {
    const auto got = std::size_t(in.gcount());
    lines += std::uint64_t(std::count(block.begin(), block.begin() + std::ptrdiff_t(got), '\n'));
    last = block[got - 1];
  }
  return lines + (last != '\n');
}

namespace {

std::size_t buffer_bytes_of(std::uint64_t budget) {
  return std::size_t(std::clamp<std::uint64_t>(budget / 8, 1 << 16, std::uint64_t(64) << 20));
}

// The least budget that holds `bytes` beside the tiles' store, whose buffer grows with the
// budget (buffer_bytes_of: an eighth of it, within 64 KiB and 64 MiB). What a budget holds
// beside the buffer never shrinks as the budget grows: bisection.
std::uint64_t least_budget(std::uint64_t bytes) {
  std::uint64_t lo = bytes, hi = bytes + (std::uint64_t(64) << 20);
  while (lo < hi) {
    const std::uint64_t mid = lo + (hi - lo) / 2;
    if (mid >= bytes + buffer_bytes_of(mid)) hi = mid;
    else lo = mid + 1;
  }
  return lo;
}

}  // namespace

MemoryPlan plan_memory(const std::filesystem::path& file, std::uint64_t budget, const MemoryCosts& costs) {
  MemoryPlan plan;
  plan.budget = budget;
  plan.points = point_count_at_most(file);
  if (plan.points * costs.in_core <= budget) return plan;
  plan.tiled = true;
  plan.buffer_bytes = buffer_bytes_of(budget);
  const std::uint64_t held = plan.points * costs.held + plan.buffer_bytes;
  // A tile's halo may hold as many points again on each side: four times its own.
  const std::uint64_t tile_bytes = 4 * costs.tile;
  if (held + kLeastTilePoints * tile_bytes > budget) {
    // The least budget that serves: tiles of the fewest points, or in core where that is less
    // (a small cloud, whose tiles' halos and buffer cost more than the cloud itself).
    const std::uint64_t least = std::min(plan.points * costs.in_core,
                                         least_budget(plan.points * costs.held + kLeastTilePoints * tile_bytes));
    const std::uint64_t kib = std::max<std::uint64_t>((least + 1023) / 1024, 1024);  // --memory takes 1M at least
    throw Error("--memory " + byte_size(double(budget)) + " is too small for " + file.string() + "'s " +
                std::to_string(plan.points) + " points: it needs at least " + std::to_string(kib) +
                " KiB (--memory " + std::to_string(kib) + "K)");  // in KiB: MiB may round to the budget's figure
  }
  plan.points_per_tile = (budget - held) / tile_bytes;
  return plan;
}

MemoryPlan spread_over_ranks(MemoryPlan plan, int ranks) {
  if (plan.tiled || ranks < 2) return plan;
  const std::uint64_t tiles = 4 * std::uint64_t(ranks);
  const std::uint64_t points_per_tile = std::max(kLeastTilePoints, (plan.points + tiles - 1) / tiles);
  if (points_per_tile >= plan.points) return plan;
  plan.tiled = true;
  plan.points_per_tile = points_per_tile;
  plan.buffer_bytes = buffer_bytes_of(plan.budget);
  return plan;
}

}  // namespace pss
