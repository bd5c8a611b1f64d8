// The two kernels of a mesh's implicit (issue 27), written once for the implicit of a cloud's
// PSS (cloud_implicit.hpp) and of a volume's (volume_implicit.hpp), on either backend. An
// implicit is a struct of views with
//   PSS_HOST_DEVICE SignedDistance operator()(vec3 x) const;
// its signed distance at x along the surface's outward normal to the projection P(x):
// f(x) = (x − P(x))·n, zero exactly where x lies on the surface (x = P(x)).
#pragma once

#include <cstdint>

#include "pss/mesh/implicit.hpp"

namespace pss {

struct SignedDistance {
  float distance;
  vec3 surface_point, normal;  // P(x), and the outward unit normal there
  bool valid;                  // a projection the data back, which may be trusted
  bool on_surface = true;      // false: f gives x's side, from the data, and surface_point is x
  bool side_from_data = false;  // the data put x on f's side: a volume's iso-surface
};

// out[i] = the implicit at corners[i].
template <class Implicit>
struct SampleCornersKernel {
  Implicit implicit;
  const vec3* corners;
  CornerSample* out;
  PSS_HOST_DEVICE void operator()(std::int64_t i) const {
    const SignedDistance s = implicit(corners[i]);
    out[i] = {s.distance, s.surface_point, s.valid, s.on_surface, s.side_from_data};
  }
};

// A vertex strictly inside its edge, no nearer an end than this share of the edge, so that
// no triangle degenerates where the surface passes through or near a corner. At 10⁻³ such
// slivers meet their neighbours at angles of 10⁻³ that the common checkers' tolerances
// take for crossings (Open3D: 14 pairs of a sphere's 23,384 triangles, 7 at 3·10⁻³, none at
// 10⁻²), though in exact arithmetic on the written floats none cross. Where the surface
// passes that near a corner its vertex lies off it by at most this share of its edge.
inline constexpr float kEdgeMargin = 1e-2f;

// out[i] = the root of f on edges[i], by regula falsi (each step a projection; the bracket
// keeps the root on the edge), until |f| <= tolerance or `steps` projections; the normal is
// the surface's at the root. f is nearly linear along an edge, so the secant lands close:
// 1.95 projections per vertex on the bunny, 2.33 on hippo1 (Illinois's rule, which keeps an
// end from sticking, measured no fewer). The vertex's normal is the implicit's vertex_normal
// of the last projection (RIMLS's filtered one costs a fit: once a vertex, not a step).
template <class Implicit>
struct CrossEdgesKernel {
  Implicit implicit;
  const EdgeCrossing* edges;
  MeshVertex* out;
  float tolerance;
  int steps;
  PSS_HOST_DEVICE void operator()(std::int64_t i) const {
    const EdgeCrossing e = edges[i];
    float lo = 0, hi = 1, f_lo = e.distance_a, f_hi = e.distance_b;
    float t = f_lo / (f_lo - f_hi);
    SignedDistance last{0.0f, vec3(0.0f), vec3(0.0f), false};
    for (int k = 0; k < steps; ++k) {
      t = min(max(t, kEdgeMargin), 1 - kEdgeMargin);
      const SignedDistance s = implicit(e.a + t * (e.b - e.a));
      if (!s.valid) break;
      last = s;
      if (abs(s.distance) <= tolerance) break;
      if ((s.distance < 0) == (f_lo < 0)) {
        lo = t;
        f_lo = s.distance;
      } else {
        hi = t;
        f_hi = s.distance;
      }
      t = lo + (hi - lo) * (f_lo / (f_lo - f_hi));
    }
    t = min(max(t, kEdgeMargin), 1 - kEdgeMargin);
    vec3 normal = last.valid ? implicit.vertex_normal(last) : vec3(0.0f);
    if (!(length2(normal) > 0)) normal = glm::normalize(e.distance_a < 0 ? e.b - e.a : e.a - e.b);
    out[i] = {e.a + t * (e.b - e.a), normal};
  }
};

}  // namespace pss
