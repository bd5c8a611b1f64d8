#include "support/shapes.hpp"

#include "pss/points/spacing.hpp"
#include "pss/points/support.hpp"

#include <cmath>
#include <numbers>
#include <random>

namespace pss::test {

namespace {

constexpr float kPi = std::numbers::pi_v<float>;

// Rejection keeps a sample with probability density(p) / 1; nonuniform densities fall
// from 1 to 0.1 along x, so the sparse side has ~10x fewer samples per area; a step divides
// the density of the half x < 0.
float density(vec3 unit_position, const SampleOptions& o) {
  const float d = o.nonuniform ? 0.1f + 0.9f * (0.5f + 0.5f * unit_position.x) : 1.0f;
  return unit_position.x < 0 ? d / o.step : d;
}

}  // namespace

float Torus::distance(vec3 p) const {
  const float q = std::sqrt(p.x * p.x + p.y * p.y) - major;
  return std::sqrt(q * q + p.z * p.z) - minor;
}

vec3 Torus::normal(vec3 p) const {
  const float rho = std::sqrt(p.x * p.x + p.y * p.y);
  const vec3 ring(major * p.x / rho, major * p.y / rho, 0.0f);
  return glm::normalize(p - ring);
}

PointCloud sample(const Sphere& s, const SampleOptions& o) {
  std::mt19937 rng(o.seed);
  std::normal_distribution<float> gauss(0.0f, 1.0f);
  std::uniform_real_distribution<float> uni(0.0f, 1.0f);
  PointCloud cloud;
  while (cloud.size() < o.count) {
    vec3 d(gauss(rng), gauss(rng), gauss(rng));
    if (glm::length(d) < 1e-6f) continue;
    d = glm::normalize(d);
    if (uni(rng) > density(d, o)) continue;
    cloud.positions.push_back(s.center + (s.radius + o.noise * gauss(rng)) * d);
  }
  return cloud;
}

PointCloud sample(const Torus& t, const SampleOptions& o) {
  std::mt19937 rng(o.seed);
  std::normal_distribution<float> gauss(0.0f, 1.0f);
  std::uniform_real_distribution<float> uni(0.0f, 1.0f);
  PointCloud cloud;
  while (cloud.size() < o.count) {
    const float u = 2 * kPi * uni(rng), v = 2 * kPi * uni(rng);
    // Area element ∝ R + r cos v: accept with that weight for uniform density on the surface.
    if (uni(rng) * (t.major + t.minor) > t.major + t.minor * std::cos(v)) continue;
    const vec3 n(std::cos(v) * std::cos(u), std::cos(v) * std::sin(u), std::sin(v));
    const vec3 p((t.major + t.minor * std::cos(v)) * std::cos(u), (t.major + t.minor * std::cos(v)) * std::sin(u),
                 t.minor * std::sin(v));
    if (uni(rng) > density(vec3(std::cos(u), 0, 0), o)) continue;
    cloud.positions.push_back(p + o.noise * gauss(rng) * n);
  }
  return cloud;
}

float Pill::distance(vec3 p) const {
  const float beyond = std::max(0.0f, std::hypot(p.x, p.y) - radius);
  return std::hypot(beyond, p.z) - half;
}

vec3 Pill::normal(vec3 p) const {
  const float rho = std::hypot(p.x, p.y);
  const vec3 nearest = rho > radius ? vec3(p.x, p.y, 0.0f) * (radius / rho) : vec3(p.x, p.y, 0.0f);
  return glm::normalize(p - nearest);
}

PointCloud sample(const Pill& pill, const SampleOptions& o) {
  std::mt19937 rng(o.seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  const float disc = kPi * pill.radius * pill.radius, rim = 2 * kPi * pill.radius * kPi * pill.half;
  PointCloud cloud;
  while (cloud.size() < o.count) {
    const float pick = u(rng) * (2 * disc + rim), angle = 2 * kPi * u(rng);
    const vec3 radial(std::cos(angle), std::sin(angle), 0.0f);
    if (pick < 2 * disc) {  // a face, evenly by area
      const float side = pick < disc ? 1.0f : -1.0f;
      cloud.positions.push_back(pill.radius * std::sqrt(u(rng)) * radial + vec3(0, 0, side * pill.half));
      cloud.normals.push_back(vec3(0, 0, side));
    } else {  // the rim, a half tube (its area element ∝ R + half·cos φ ≈ R)
      const float phi = kPi * (u(rng) - 0.5f);
      const vec3 n = std::cos(phi) * radial + vec3(0, 0, std::sin(phi));
      cloud.positions.push_back(pill.radius * radial + pill.half * n);
      cloud.normals.push_back(n);
    }
  }
  return cloud;
}

PointCloud sample_plane(float half_size, const SampleOptions& o) {
  std::mt19937 rng(o.seed);
  std::normal_distribution<float> gauss(0.0f, 1.0f);
  std::uniform_real_distribution<float> uni(-1.0f, 1.0f);
  PointCloud cloud;
  while (cloud.size() < o.count) {
    const vec3 unit(uni(rng), uni(rng), 0.0f);
    if (0.5f * (uni(rng) + 1) > density(unit, o)) continue;
    cloud.positions.push_back(vec3(half_size * unit.x, half_size * unit.y, o.noise * gauss(rng)));
  }
  return cloud;
}

PointCloud sheet_and_ball(std::size_t sheet_points, const Sphere& ball, std::size_t ball_points) {
  SampleOptions o;
  o.count = sheet_points;
  PointCloud cloud = sample_plane(1.0f, o);
  o.count = ball_points;
  const PointCloud on_ball = sample(ball, o);
  cloud.positions.insert(cloud.positions.end(), on_ball.positions.begin(), on_ball.positions.end());
  return cloud;
}

float ShapeCase::radius() const { return torus ? Torus{}.minor : Sphere{}.radius; }

PointCloud ShapeCase::sample() const {
  SampleOptions o;
  o.count = count ? count : torus ? 12000 : 5000;
  o.noise = noise_sigma();
  o.nonuniform = nonuniform;
  o.step = step;
  return torus ? test::sample(Torus{}, o) : test::sample(Sphere{}, o);
}

float suggested_h(const PointCloud& cloud) { return float(estimate_spacing(cloud.positions).suggested_h); }

SupportGrid support_grid(std::span<const vec3> points, const ProjectionParams& params) {
  return SupportGrid(points, support_widths(points, params).h, params.rho / params.h);
}

std::vector<vec3> noisy_sphere_with_strays(std::size_t strays, std::size_t every, unsigned seed) {
  SampleOptions o;
  o.count = 12000;
  o.noise = 0.02f;
  std::vector<vec3> points = sample(Sphere{}, o).positions;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> off(-0.3f, 0.3f);
  for (std::size_t i = 0; i < strays; ++i) points.push_back(points[i * every] * (1 + off(rng)));
  return points;
}

}  // namespace pss::test
