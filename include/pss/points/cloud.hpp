// A point cloud on the host: positions and, when the file has them, unit normals and colours.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/ext/vector_uint3_sized.hpp>

#include "pss/core/types.hpp"

namespace pss {

// 8 bits per channel, as the formats' colours nearly always are (PLY uchar, PCD packed rgb);
// wider or float colours are scaled to 0..255 by the readers.
using Rgb8 = glm::u8vec3;

struct PointCloud {
  std::vector<vec3> positions;
  std::vector<vec3> normals;  // empty, or one per position
  std::vector<Rgb8> colors;   // empty, or one per position

  std::size_t size() const { return positions.size(); }
  bool has_normals() const { return !normals.empty(); }
  bool has_colors() const { return !colors.empty(); }
  Aabb bounds() const {
    Aabb box;
    for (const vec3& p : positions) box.grow(p);
    return box;
  }
};

}  // namespace pss
