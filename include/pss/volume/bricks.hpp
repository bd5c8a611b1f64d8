// Empty-space skipping: the volume's cells grouped into bricks of kBrickCells³, each marked
// when some sample inside could pass the fragment test (§5.1), from the min/max of its
// voxels. Rays jump over unmarked bricks to the next sample of their step lattice, so the
// samples (and hence the image) are exactly those of marching without skipping.
#pragma once

#include <cstdint>
#include <vector>

#include "pss/volume/fields.hpp"

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

// Trilinear values and gradient magnitudes inside a cell are bounded by the cell's corner
// values, so a brick whose voxels (its cells' corners) cannot pass is skipped safely.
BrickGrid build_bricks(const VolumeFields& fields, const FeatureParams& feature);

}  // namespace pss
