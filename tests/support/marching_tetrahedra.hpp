// The mesh baseline the PSS is compared against on noisy volumes: the vertices of a
// marching-tetrahedra iso-surface (each cube split into six tetrahedra around its main
// diagonal), placed by linear interpolation on the edges that cross the iso-value, with
// normals from the central-difference gradient interpolated along the same edge. Only the
// vertices and normals are needed, so no triangles are built.
#pragma once

#include <vector>

#include "pss/volume/volume.hpp"

namespace pss::test {

struct MeshVertex {
  vec3 point;
  vec3 normal;  // along ∇f
};

inline vec3 central_difference(const VolumeView& v, int i, int j, int k) {
  const auto at = [&](int x, int y, int z) {
    return v.at(clamp(x, 0, v.dims.x - 1), clamp(y, 0, v.dims.y - 1), clamp(z, 0, v.dims.z - 1));
  };
  return vec3((at(i + 1, j, k) - at(i - 1, j, k)) / (2 * v.spacing.x),
              (at(i, j + 1, k) - at(i, j - 1, k)) / (2 * v.spacing.y),
              (at(i, j, k + 1) - at(i, j, k - 1)) / (2 * v.spacing.z));
}

inline std::vector<MeshVertex> marching_tetrahedra_vertices(const VolumeView& v, float iso) {
  // The Freudenthal (Kuhn) split of every cube into six tetrahedra around its main
  // diagonal has, as its edges, the steps s ∈ {0, 1}³ ∖ {0} from every voxel: each grid
  // edge is visited once.
  static const ivec3 steps[7] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 0}, {1, 0, 1}, {0, 1, 1}, {1, 1, 1}};
  std::vector<MeshVertex> out;
  for (int k = 0; k < v.dims.z; ++k)
    for (int j = 0; j < v.dims.y; ++j)
      for (int i = 0; i < v.dims.x; ++i)
        for (const ivec3& s : steps) {
          const int i2 = i + s.x, j2 = j + s.y, k2 = k + s.z;
          if (i2 >= v.dims.x || j2 >= v.dims.y || k2 >= v.dims.z) continue;
          const float a = v.at(i, j, k) - iso, b = v.at(i2, j2, k2) - iso;
          if ((a < 0) == (b < 0)) continue;
          const float w = a / (a - b);
          const vec3 p = v.position(i, j, k) + w * (v.position(i2, j2, k2) - v.position(i, j, k));
          const vec3 g = (1 - w) * central_difference(v, i, j, k) + w * central_difference(v, i2, j2, k2);
          if (!(length2(g) > 0)) continue;
          out.push_back({p, glm::normalize(g)});
        }
  return out;
}

}  // namespace pss::test
