#include "pss/tiles/farm.hpp"

#include "pss/core/error.hpp"
#include "pss/core/memory.hpp"
#include "tile_works.hpp"

namespace pss {

std::vector<std::byte> tile_work(TileStep step, std::span<const std::byte> request) {
  switch (step) {
    case TileStep::outliers:
      return work_outliers(request);
    case TileStep::projection:
      return work_projection(request);
    case TileStep::orientation:
      return work_orientation(request);
    case TileStep::spacing:
      return work_spacing(request);
    case TileStep::widths:
      return work_widths(request);
    case TileStep::sample_normals:
      return work_sample_normals(request);
    case TileStep::mesh:
      return work_mesh(request);
    case TileStep::seam_turn:
      return work_seam_turn(request);
    case TileStep::file_normals:
      return work_file_normals(request);
  }
  throw Error("a tile's work names no step");
}

namespace {

class LocalFarm final : public TileFarm {
 public:
  int ranks() const override { return 1; }
  void run(TileStep step, std::span<const int> tiles, const Request& request, const Take& take) override {
    for (const int tile : tiles) {
      TileRequest asked = request(tile);
      const std::vector<std::byte> result = tile_work(step, asked.work);
      release(asked.work);
      take(tile, result, asked.notes, 0);
    }
  }
};

}  // namespace

TileFarm& local_farm() {
  static LocalFarm farm;
  return farm;
}

}  // namespace pss
