// A point cloud on the host: positions and, when the file has them, unit normals, colours and
// other per-point scalar properties.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <glm/ext/vector_uint3_sized.hpp>

#include "pss/core/types.hpp"

namespace pss {

// 8 bits per channel, as the formats' colours nearly always are (PLY uchar, PCD packed rgb);
// wider or float colours are scaled to 0..255 by the readers.
using Rgb8 = glm::u8vec3;

// A scalar property's type as the file stores it (PLY's char, uchar, ... double).
enum class ScalarType { int8, uint8, int16, uint16, int32, uint32, float32, float64 };

// A per-point value beyond position, normal and colour (a scanner's intensity or confidence,
// a label): pss does not use it, but keeps it so that outputs can carry it through. A double
// holds a value of every ScalarType exactly.
struct ScalarProperty {
  std::string name;
  ScalarType type = ScalarType::float32;
  std::vector<double> values;  // one per position
};

struct PointCloud {
  std::vector<vec3> positions;
  std::vector<vec3> normals;            // empty, or one per position
  std::vector<Rgb8> colors;             // empty, or one per position
  std::vector<ScalarProperty> scalars;  // in the file's order

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
