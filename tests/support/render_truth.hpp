// A rendered frame against an analytic sphere (issue 26's noise and outliers, for each
// surface kind on both backends): pixels whose ray meets the sphere but found no surface
// near it (holes), hits off it (extra surface), and the hits' distance and normal error.
#pragma once

#include <cstdint>

#include "pss/backend/backend.hpp"
#include "pss/points/cloud.hpp"
#include "pss/points/projection.hpp"
#include "pss/points/ray_pss.hpp"
#include "pss/render/camera.hpp"
#include "pss/render/rendered_frame.hpp"
#include "shapes.hpp"

namespace pss::test {

// A unit sphere of `count` samples with Gaussian noise of `noise_in_spacing` times their
// spacing along the normal, and `outlier_fraction` of that count as strays: half 1 to 3
// widths off the sphere, half strewn through its box (seeded).
PointCloud noisy_sphere_with_strays(std::size_t count, float noise_in_spacing, float outlier_fraction);

struct RenderTruth {
  std::int64_t data_pixels = 0;  // rays that meet the sphere, not grazing it (cos > 0.3)
  std::int64_t holes = 0;        // of those, without a hit within `near` of the sphere at its first crossing
  std::int64_t extra = 0;        // hits farther than `near` from the sphere, or where the ray misses it
  double mean_distance = 0;      // of the hits within `near`, to the sphere
  double mean_normal_deg = 0;    // of the same hits, against the sphere's normal (unsigned)
  double hole_fraction() const { return double(holes) / double(data_pixels); }
  double extra_fraction() const { return double(extra) / double(data_pixels); }
};

RenderTruth against_sphere(const RenderedFrame& frame, const Sphere& sphere, float near);

// A cube [-1, 1]³ with a bore of radius 0.4 along z (issue 26's CAD part: creases, circular
// rims, known normals). The solid is the box minus the cylinder.
struct BoredBox {
  float bore = 0.4f;
  float distance(vec3 p) const;  // signed, negative inside: exact near the faces, a bound elsewhere
  vec3 normal(vec3 p) const;     // outward, of the nearest face
  float to_crease(vec3 p) const;  // from a point on the surface to the nearest edge or rim
};

// Its surface on a grid of `spacing` (half a step off the edges), with the exact normals;
// bore 0: the plain box.
PointCloud sample(const BoredBox& box, float spacing);

struct CreaseTruth {
  std::int64_t data_pixels = 0, holes = 0, extra = 0;  // as RenderTruth's
  double flat_normal_deg = 0;   // mean over the hits farther than 3 widths from a crease
  double crease_normal_deg = 0;  // mean over the hits 0.5 to 2 widths from one
};

// The frame against the bored box (sphere tracing finds each ray's first crossing); `h` sets
// the bands of flat_normal_deg and crease_normal_deg.
CreaseTruth against_bored_box(const RenderedFrame& frame, const BoredBox& box, float near, float h);

// `cloud` rendered with `params` on `backend` at 160², no shadows or reflections, from
// (azimuth, elevation) about `up`, framing `frame`.
RenderedFrame render_at_160(const PointCloud& cloud, const RayPssParams& params, Backend backend, const Aabb& frame,
                            float azimuth_deg, float elevation_deg, vec3 up = vec3(0, 1, 0));

// `cloud` (a unit sphere's samples, and strays) rendered at 160² on `backend` with the
// default parameters, this surface and outlier policy, against the unit sphere (near: 0.05).
RenderTruth render_sphere(const PointCloud& cloud, SurfaceOperator surface, OutlierPolicy outliers, Backend backend);

// Prints t and checks it (gtest) against issue 26's goals for noise and outliers: holes
// <= 0.3 % and extra surface <= 0.2 % of the sphere's pixels; the hits within 0.4 σ of it
// (σ = 0.016, noisy_sphere_with_strays(12000, 0.5, ·)) and their normals within 6 degrees.
void expect_like_the_sphere(const RenderTruth& t, const char* name);

// An open square [-1, 1]² at z = 0 (4,000 samples at random, spacing about 0.03) rendered at
// 160² from above and aside with these borders and surface on `backend`: the widest reach of
// a hit past the square's edge, in h, and the pixels whose ray meets the square at least 2h
// inside its edge and found no hit there (within 0.01).
struct BorderTruth {
  std::int64_t inner_pixels = 0, holes = 0;
  std::int64_t beyond = 0;    // hits more than 0.25h past the edge
  double overshoot = 0;       // the farthest hit past the edge, in h (0: none)
};
BorderTruth render_open_square(BorderMode borders, SurfaceOperator surface, Backend backend);

}  // namespace pss::test
