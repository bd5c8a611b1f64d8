// The mesh baseline the PSS is compared against on noisy volumes: the vertices of a
// marching-tetrahedra iso-surface (each cube split into six tetrahedra around its main
// diagonal), placed by linear interpolation on the edges that cross the iso-value, with
// normals from the central-difference gradient interpolated along the same edge. The
// vertices alone serve the noise measurements; the triangles (marching_tetrahedra_triangles)
// make the mesh of the real-data reference (iso_reference.hpp).
#pragma once

#include <cmath>
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

struct Triangle {
  vec3 a, b, c;
};

// The triangles of the same surface: in each of a cube's six tetrahedra (corners 0, e_a,
// e_a + e_b, e_a + e_b + e_c for each order (a, b, c) of the axes: the Freudenthal split,
// whose faces match between neighbouring cubes, so the mesh has no cracks), one triangle
// where one corner is on its own side of iso, two where the corners split two and two.
// "Below" is value < iso, as in marching_tetrahedra_vertices; orientation is not kept.
inline std::vector<Triangle> marching_tetrahedra_triangles(const VolumeView& v, float iso) {
  static const int orders[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  std::vector<Triangle> out;
  for (int k = 0; k + 1 < v.dims.z; ++k)
    for (int j = 0; j + 1 < v.dims.y; ++j)
      for (int i = 0; i + 1 < v.dims.x; ++i) {
        float lo = kInfinity, hi = -kInfinity;
        for (int c = 0; c < 8; ++c) {
          const float x = v.at(i + (c & 1), j + (c >> 1 & 1), k + (c >> 2));
          lo = std::fmin(lo, x);
          hi = std::fmax(hi, x);
        }
        if (!(lo < iso && hi >= iso)) continue;
        for (const auto& order : orders) {
          ivec3 corner[4] = {ivec3(i, j, k)};
          for (int n = 1; n < 4; ++n) {
            corner[n] = corner[n - 1];
            corner[n][order[n - 1]] += 1;
          }
          float f[4];
          vec3 p[4];
          int below = 0, mask = 0;
          for (int n = 0; n < 4; ++n) {
            f[n] = v.at(corner[n].x, corner[n].y, corner[n].z) - iso;
            p[n] = v.position(corner[n].x, corner[n].y, corner[n].z);
            if (f[n] < 0) {
              ++below;
              mask |= 1 << n;
            }
          }
          if (below == 0 || below == 4) continue;
          const auto cut = [&](int a, int b) { return p[a] + f[a] / (f[a] - f[b]) * (p[b] - p[a]); };
          if (below == 1 || below == 3) {
            // The corner alone on its side, and the three edges from it.
            int lone = 0;
            for (int n = 0; n < 4; ++n)
              if (((mask >> n & 1) != 0) == (below == 1)) lone = n;
            int others[3], m = 0;
            for (int n = 0; n < 4; ++n)
              if (n != lone) others[m++] = n;
            out.push_back({cut(lone, others[0]), cut(lone, others[1]), cut(lone, others[2])});
          } else {
            // Below {a, b}, above {c, d}: the quad a–c, a–d, b–d, b–c.
            int side[2][2], nb = 0, na = 0;
            for (int n = 0; n < 4; ++n) {
              if (mask >> n & 1)
                side[0][nb++] = n;
              else
                side[1][na++] = n;
            }
            const int a = side[0][0], b = side[0][1], c = side[1][0], d = side[1][1];
            const vec3 ac = cut(a, c), ad = cut(a, d), bd = cut(b, d), bc = cut(b, c);
            out.push_back({ac, ad, bd});
            out.push_back({ac, bd, bc});
          }
        }
      }
  return out;
}

}  // namespace pss::test
