#include "pss/volume/bricks.hpp"

#include <algorithm>

#include "pss/backend/cpu/parallel_for.hpp"

namespace pss {

BrickGrid build_bricks(const SurfaceCells& cells) {
  BrickGrid grid;
  grid.count = (cells.count + kBrickCells - 1) / kBrickCells;
  grid.occupied.assign(std::size_t(grid.count.x) * grid.count.y * grid.count.z, 0);
  const CellView view = cells.view();
  cpu::parallel_for(std::int64_t(grid.occupied.size()), [&](std::int64_t b) {
    const int bx = int(b % grid.count.x), by = int(b / grid.count.x % grid.count.y);
    const int bz = int(b / (std::int64_t(grid.count.x) * grid.count.y));
    const ivec3 lo = ivec3(bx, by, bz) * kBrickCells;
    const ivec3 hi = glm::min(lo + kBrickCells, cells.count);
    bool reached = false;
    for (int k = lo.z; k < hi.z && !reached; ++k)
      for (int j = lo.y; j < hi.y && !reached; ++j)
        for (int i = lo.x; i < hi.x && !reached; ++i) reached = view.at(ivec3(i, j, k)) & kCellInReach;
    grid.occupied[std::size_t(b)] = reached ? 1 : 0;
  });
  grid.occupied_count = std::count(grid.occupied.begin(), grid.occupied.end(), std::uint8_t(1));
  return grid;
}

}  // namespace pss
