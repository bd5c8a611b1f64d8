// Implicits known exactly, for the march's tests: the zero set of a signed distance, its
// roots found by bisection to float precision, and the march over them.
#pragma once

#include <functional>
#include <span>

#include "pss/mesh/marching_tetrahedra.hpp"
#include "pss/mesh/mesh_cloud.hpp"

namespace pss::test {

// An implicit given by its exact signed distance and gradient; valid where `valid` says.
inline ImplicitSurface analytic(std::function<float(vec3)> distance, std::function<vec3(vec3)> normal,
                         std::function<bool(vec3)> valid = [](vec3) { return true; }) {
  ImplicitSurface s;
  s.sample = [=](std::span<const vec3> corners, std::span<CornerSample> out, Progress&) {
    for (std::size_t i = 0; i < corners.size(); ++i) {
      const float d = distance(corners[i]);
      out[i] = {d, corners[i] - d * normal(corners[i]), valid(corners[i])};
    }
  };
  s.cross = [=](std::span<const EdgeCrossing> edges, std::span<MeshVertex> out) {
    for (std::size_t i = 0; i < edges.size(); ++i) {  // bisection, to float precision
      const EdgeCrossing& e = edges[i];
      float lo = 0, hi = 1;
      for (int k = 0; k < 40; ++k) {
        const float t = 0.5f * (lo + hi);
        ((distance(e.a + t * (e.b - e.a)) < 0) == (e.distance_a < 0) ? lo : hi) = t;
      }
      const vec3 p = e.a + 0.5f * (lo + hi) * (e.b - e.a);
      out[i] = {p, normal(p)};
    }
  };
  return s;
}

inline TriangleMesh march(const ImplicitSurface& s, vec3 lo, vec3 hi, float cell, std::span<const vec3> seeds,
                   MarchCounts& counts, float crease_angle = kDefaultCreaseAngle) {
  return march_tetrahedra(lattice_over(lo, hi, 2 * cell, cell, "cell"), seeds, s, 1.0f, crease_angle, counts);
}

}  // namespace pss::test
