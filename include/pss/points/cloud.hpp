// A point cloud on the host: positions and, when the file has them, unit normals.
#pragma once

#include <vector>

#include "pss/core/types.hpp"

namespace pss {

struct PointCloud {
  std::vector<vec3> positions;
  std::vector<vec3> normals;  // empty, or one per position

  std::size_t size() const { return positions.size(); }
  bool has_normals() const { return !normals.empty(); }
  Aabb bounds() const {
    Aabb box;
    for (const vec3& p : positions) box.grow(p);
    return box;
  }
};

}  // namespace pss
