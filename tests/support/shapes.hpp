// Analytic shapes for tests: seeded samplers (uniform or strongly non-uniform density, with
// optional Gaussian noise along the normal) and exact distances and normals to check against.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "pss/points/cloud.hpp"
#include "pss/points/projection.hpp"
#include "pss/spatial/support_grid.hpp"

namespace pss::test {

struct Sphere {
  vec3 center{0.0f};
  float radius = 1.0f;
  float distance(vec3 p) const { return glm::length(p - center) - radius; }
  vec3 normal(vec3 p) const { return glm::normalize(p - center); }
};

// Torus around the z axis: R from the axis to the tube's centre line, tube radius r.
struct Torus {
  float major = 1.0f, minor = 0.35f;
  float distance(vec3 p) const;
  vec3 normal(vec3 p) const;
};

// A thin closed part: the points within `half` of the disc of `radius` at z = 0 about the z
// axis (two flat faces 2·half apart, joined by a rounded rim).
struct Pill {
  float radius = 1.0f, half = 0.03f;
  float distance(vec3 p) const;
  vec3 normal(vec3 p) const;
};

struct Plane {  // z = 0
  float distance(vec3 p) const { return p.z; }
  vec3 normal(vec3) const { return vec3(0, 0, 1); }
};

struct SampleOptions {
  std::size_t count = 4000;
  float noise = 0;            // standard deviation of the offset along the normal
  bool nonuniform = false;    // density varying about 10× across the shape
  float step = 1;             // the half x < 0 (of the unit shape) sampled this many times sparser
  std::uint32_t seed = 1;
};

PointCloud sample(const Sphere& s, const SampleOptions& o);
PointCloud sample(const Torus& t, const SampleOptions& o);
PointCloud sample_plane(float half_size, const SampleOptions& o);  // square [-a, a]² at z = 0
// The square [-1, 1]² at z = 0 of `sheet_points` points and `ball_points` on the sphere `ball`.
PointCloud sheet_and_ball(std::size_t sheet_points, const Sphere& ball, std::size_t ball_points);
// 12,000 samples of the unit sphere with noise 0.02, and `strays` more: the samples 0, every,
// 2·every, ... each moved up to 30 % along its radius (seeded by `seed`).
std::vector<vec3> noisy_sphere_with_strays(std::size_t strays, std::size_t every, unsigned seed);
// Evenly by area, faces and rim, with the exact outward normals (no noise, uniform density).
PointCloud sample(const Pill& pill, const SampleOptions& o);

// One case of the accuracy tests: a unit sphere or the default torus, uniform or 10:1
// non-uniform density, with Gaussian noise relative to the radius of curvature.
struct ShapeCase {
  const char* name;
  bool torus;
  bool nonuniform;
  float noise;  // relative to radius()
  float step = 1;  // SampleOptions::step
  std::size_t count = 0;  // samples; 0: 12,000 of the torus, 5,000 of the sphere

  float radius() const;  // the sphere's radius or the torus's tube radius: 1/κ of the largest curvature
  float noise_sigma() const { return noise * radius(); }
  PointCloud sample() const;
};

// The h `pss` would choose for the cloud (points/spacing.hpp).
float suggested_h(const PointCloud& cloud);

// The range-query grid of `points` with the widths that params.support gives them
// (points/support.hpp), as the library's own callers build it.
SupportGrid support_grid(std::span<const vec3> points, const ProjectionParams& params);

}  // namespace pss::test
