// Empty-space skipping: the volume's cells grouped into bricks of kBrickCells³, each marked
// when one of its cells is within reach of the surface (surface_cells.hpp), so that no
// sample inside an unmarked brick could be projected. Rays jump over unmarked bricks to the
// next sample of their step lattice, so the samples (and hence the image) are exactly those
// of marching without skipping.
#pragma once

#include <cstdint>
#include <vector>

#include "pss/volume/surface_cells.hpp"

namespace pss {

inline constexpr int kBrickCells = 8;

struct BrickView {
  const std::uint8_t* occupied = nullptr;
  ivec3 count{0};

  PSS_HOST_DEVICE ivec3 brick_of(vec3 grid) const {
    const ivec3 b(int(floor(grid.x / kBrickCells)), int(floor(grid.y / kBrickCells)), int(floor(grid.z / kBrickCells)));
    return glm::clamp(b, ivec3(0), count - 1);
  }
  PSS_HOST_DEVICE bool is_occupied(ivec3 b) const { return occupied[(b.z * count.y + b.y) * count.x + b.x] != 0; }
};

struct BrickGrid {
  std::vector<std::uint8_t> occupied;
  ivec3 count{0};
  std::int64_t occupied_count = 0;

  BrickView view() const { return {occupied.data(), count}; }
};

BrickGrid build_bricks(const SurfaceCells& cells);

}  // namespace pss
