// Where the tiles of a step are worked on (issue 28): in this process, one after another, or
// spread over processes (`mpirun -np N pss project`: apps/pss/ranks). A tile's work is a pure
// function of its request's bytes (tile_work), so that any process gives the same result and
// the output does not depend on how many processes shared it.
#pragma once

#include <cstddef>
#include <functional>
#include <span>
#include <vector>

namespace pss {

enum class TileStep : int {
  outliers = 1,
  projection = 2,
  orientation = 3,
  spacing = 4,
  widths = 5,
  sample_normals = 6,
  mesh = 7,
  seam_turn = 8,
  file_normals = 9
};

// The result's bytes of a tile's work. Throws Error where the request does not hold together.
std::vector<std::byte> tile_work(TileStep step, std::span<const std::byte> request);

// A tile's work, and the notes of the process that asked for it (which of the cloud's points
// are the tile's own, ...), carried with the work and given back with its result untouched,
// so that the asking process holds nothing for a tile while another works on it.
struct TileRequest {
  std::vector<std::byte> work;
  std::vector<std::byte> notes;
};

class TileFarm {
 public:
  using Request = std::function<TileRequest(int tile)>;
  using Take =
      std::function<void(int tile, std::span<const std::byte> result, std::span<const std::byte> notes, int rank)>;

  virtual ~TileFarm() = default;
  virtual int ranks() const = 0;
  // For each of `tiles`: request(tile) here, tile_work of its work in some rank, then
  // take(tile, result, notes, that rank) here, in the order of `tiles`.
  virtual void run(TileStep step, std::span<const int> tiles, const Request& request, const Take& take) = 0;
};

// This process alone: each tile's request, work and result in turn.
TileFarm& local_farm();

}  // namespace pss
