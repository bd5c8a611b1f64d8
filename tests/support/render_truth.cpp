#include "render_truth.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

#include "pss/points/render_cloud.hpp"

namespace pss::test {

PointCloud noisy_sphere_with_strays(std::size_t count, float noise_in_spacing, float outlier_fraction) {
  SampleOptions o;
  o.count = count;
  const float spacing = std::sqrt(4 * 3.14159265f / float(count));
  o.noise = noise_in_spacing * spacing;
  PointCloud cloud = sample(Sphere{}, o);
  const float h = suggested_h(cloud);
  std::mt19937 rng(17);
  std::normal_distribution<float> gauss(0.0f, 1.0f);
  std::uniform_real_distribution<float> uni(0.0f, 1.0f);
  const auto strays = std::size_t(outlier_fraction * float(count));
  for (std::size_t i = 0; i < strays; ++i) {
    if (i % 2) {
      const vec3 d = glm::normalize(vec3(gauss(rng), gauss(rng), gauss(rng)));
      cloud.positions.push_back(d * (1 + (1 + 2 * uni(rng)) * h * (i % 4 == 1 ? 1.0f : -1.0f)));
    } else {
      cloud.positions.push_back(vec3(uni(rng), uni(rng), uni(rng)) * 3.0f - 1.5f);
    }
  }
  return cloud;
}

RenderTruth against_sphere(const RenderedFrame& frame, const Sphere& sphere, float near) {
  RenderTruth truth;
  std::int64_t on_hits = 0;
  const Camera& camera = frame.camera;
  for (int y = 0; y < camera.height; ++y)
    for (int x = 0; x < camera.width; ++x) {
      const Ray ray = camera.primary_ray(x, y);
      const Hit& hit = frame.hits[std::size_t(y) * std::size_t(camera.width) + std::size_t(x)];
      // The ray's first crossing of the sphere, if any.
      const vec3 oc = ray.origin - sphere.center;
      const float b = glm::dot(oc, ray.dir), c = glm::dot(oc, oc) - sphere.radius * sphere.radius;
      const float disc = b * b - c;
      bool meets = false;
      float t_first = kInfinity;
      if (disc > 0) {
        t_first = -b - std::sqrt(disc);
        meets = -glm::dot(sphere.normal(ray.at(t_first)), ray.dir) > 0.3f;
      }
      // On the sphere, and its first crossing where the ray meets it head on (not the far side).
      const bool on = hit.found() && std::abs(sphere.distance(hit.point)) <= near &&
                      (!meets || std::abs(hit.t - t_first) <= 4 * near);
      if (meets) {
        ++truth.data_pixels;
        truth.holes += !on;
      }
      if (hit.found() && !on) ++truth.extra;
      if (on) {
        ++on_hits;
        truth.mean_distance += std::abs(sphere.distance(hit.point));
        const float cosine = std::min(1.0f, std::abs(glm::dot(glm::normalize(hit.normal), sphere.normal(hit.point))));
        truth.mean_normal_deg += std::acos(cosine) * 180.0 / 3.14159265358979;
      }
    }
  if (on_hits > 0) {
    truth.mean_distance /= double(on_hits);
    truth.mean_normal_deg /= double(on_hits);
  }
  return truth;
}

void expect_like_the_sphere(const RenderTruth& t, const char* name) {
  std::printf("%s: %lld pixels on the sphere; holes %lld, extra %lld, distance %.2e, normals %.2f deg\n", name,
              (long long)t.data_pixels, (long long)t.holes, (long long)t.extra, t.mean_distance, t.mean_normal_deg);
  SCOPED_TRACE(name);
  ASSERT_GT(t.data_pixels, 4000);
  EXPECT_LE(t.hole_fraction(), 0.003);
  EXPECT_LE(t.extra_fraction(), 0.002);
  // The fits average the noise down to about a quarter of σ (measured on the CPU: 3.1e-3 to
  // 4.4e-3; normals 1.8 to 4.8 degrees).
  EXPECT_LT(t.mean_distance, 0.4 * 0.016);
  EXPECT_LT(t.mean_normal_deg, 6.0);
}

float BoredBox::distance(vec3 p) const {
  const vec3 q = glm::abs(p) - vec3(1.0f);
  const float box = glm::length(glm::max(q, vec3(0.0f))) + std::min(std::max(q.x, std::max(q.y, q.z)), 0.0f);
  return std::max(box, bore - std::sqrt(p.x * p.x + p.y * p.y));
}

vec3 BoredBox::normal(vec3 p) const {
  const float r = std::sqrt(p.x * p.x + p.y * p.y);
  const vec3 a = glm::abs(p);
  const float box = std::max(a.x, std::max(a.y, a.z)) - 1;
  if (bore - r > box) return -vec3(p.x, p.y, 0.0f) / r;  // the bore's wall faces its axis
  if (a.x >= a.y && a.x >= a.z) return vec3(p.x > 0 ? 1.0f : -1.0f, 0, 0);
  if (a.y >= a.z) return vec3(0, p.y > 0 ? 1.0f : -1.0f, 0);
  return vec3(0, 0, p.z > 0 ? 1.0f : -1.0f);
}

float BoredBox::to_crease(vec3 p) const {
  const float r = std::sqrt(p.x * p.x + p.y * p.y);
  const vec3 a = glm::abs(p);
  if (bore - r > std::max(a.x, std::max(a.y, a.z)) - 1) return 1 - a.z;  // on the bore: its rims
  const vec3 n = normal(p);
  float d = kInfinity;
  for (int k = 0; k < 3; ++k)
    if (n[k] == 0) d = std::min(d, 1 - a[k]);  // the face's edges
  if (n.z != 0) d = std::min(d, r - bore);  // a face the bore opens: its rim
  return d;
}

PointCloud sample(const BoredBox& box, float spacing) {
  PointCloud cloud;
  const int n = int(std::lround(2 / spacing));
  for (int axis = 0; axis < 3; ++axis)
    for (float side : {-1.0f, 1.0f})
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
          vec3 p, normal(0.0f);
          p[axis] = side;
          p[(axis + 1) % 3] = -1 + (i + 0.5f) * spacing;
          p[(axis + 2) % 3] = -1 + (j + 0.5f) * spacing;
          if (axis == 2 && p.x * p.x + p.y * p.y < box.bore * box.bore) continue;  // the bore's mouth
          normal[axis] = side;
          cloud.positions.push_back(p);
          cloud.normals.push_back(normal);
        }
  const int around = int(std::lround(2 * 3.14159265f * box.bore / spacing));
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < around; ++k) {
      const float a = 2 * 3.14159265f * (k + 0.5f) / float(around);
      const vec3 d(std::cos(a), std::sin(a), 0.0f);
      cloud.positions.push_back(box.bore * d + vec3(0, 0, -1 + (i + 0.5f) * spacing));
      cloud.normals.push_back(-d);
    }
  return cloud;
}

RenderedFrame render_at_160(const PointCloud& cloud, const RayPssParams& params, Backend backend, const Aabb& frame,
                            float azimuth_deg, float elevation_deg, vec3 up) {
  Stats stats;
  const PreparedCloud prepared(cloud, params, backend, stats);
  CameraSettings view;
  view.width = view.height = 160;
  view.azimuth_deg = azimuth_deg;
  view.elevation_deg = elevation_deg;
  view.up = up;
  const Camera camera = Camera::framing(frame, view);
  return render_cloud(prepared, camera, TraceSettings::for_camera(camera, false, false), backend, stats);
}

BorderTruth render_open_square(BorderMode borders, SurfaceOperator surface, Backend backend) {
  SampleOptions o;
  o.count = 4000;
  const PointCloud cloud = sample_plane(1.0f, o);
  const float h = suggested_h(cloud);
  RayPssParams params = RayPssParams::from_h(h);
  params.projection.surface = surface;
  params.projection.borders = borders;
  const RenderedFrame frame = render_at_160(cloud, params, backend, cloud.bounds(), 25, 60, vec3(0, 0, 1));
  const Camera& camera = frame.camera;
  BorderTruth truth;
  for (int y = 0; y < camera.height; ++y)
    for (int x = 0; x < camera.width; ++x) {
      const Ray ray = camera.primary_ray(x, y);
      const Hit& hit = frame.hits[std::size_t(y) * std::size_t(camera.width) + std::size_t(x)];
      const vec3 crossing = ray.at(-ray.origin.z / ray.dir.z);
      if (std::max(std::abs(crossing.x), std::abs(crossing.y)) < 1 - 2 * h) {
        ++truth.inner_pixels;
        truth.holes += !hit.found() || glm::length(hit.point - crossing) > 0.01f;
      }
      if (!hit.found()) continue;
      const double past = (std::max(std::abs(hit.point.x), std::abs(hit.point.y)) - 1) / h;
      truth.beyond += past > 0.25;
      truth.overshoot = std::max(truth.overshoot, past);
    }
  return truth;
}

CreaseTruth against_bored_box(const RenderedFrame& frame, const BoredBox& box, float near, float h) {
  CreaseTruth truth;
  std::int64_t flat = 0, crease = 0;
  const Camera& camera = frame.camera;
  for (int y = 0; y < camera.height; ++y)
    for (int x = 0; x < camera.width; ++x) {
      const Ray ray = camera.primary_ray(x, y);
      const Hit& hit = frame.hits[std::size_t(y) * std::size_t(camera.width) + std::size_t(x)];
      // Sphere tracing: the distance is a lower bound, so no crossing is stepped over.
      float t = 0, t_first = kInfinity;
      for (int step = 0; step < 400 && t < 100; ++step) {
        const float d = box.distance(ray.at(t));
        if (d < 1e-5f) {
          t_first = t;
          break;
        }
        t += d;
      }
      const bool meets = t_first < kInfinity && -glm::dot(box.normal(ray.at(t_first)), ray.dir) > 0.3f &&
                         box.to_crease(ray.at(t_first)) > 2 * near;
      const bool on = hit.found() && std::abs(box.distance(hit.point)) <= near &&
                      (t_first == kInfinity || hit.t <= t_first + 4 * near);
      if (meets) {
        ++truth.data_pixels;
        truth.holes += !on;
      }
      if (hit.found() && !on) ++truth.extra;
      if (!on) continue;
      const float cosine = std::min(1.0f, std::abs(glm::dot(glm::normalize(hit.normal), box.normal(hit.point))));
      const double degrees = std::acos(cosine) * 180.0 / 3.14159265358979;
      const float to_crease = box.to_crease(hit.point);
      if (to_crease > 3 * h) {
        truth.flat_normal_deg += degrees;
        ++flat;
      } else if (to_crease > 0.5f * h && to_crease < 2 * h) {
        truth.crease_normal_deg += degrees;
        ++crease;
      }
    }
  if (flat) truth.flat_normal_deg /= double(flat);
  if (crease) truth.crease_normal_deg /= double(crease);
  return truth;
}

RenderTruth render_sphere(const PointCloud& cloud, SurfaceOperator surface, OutlierPolicy outliers, Backend backend) {
  RayPssParams params = RayPssParams::from_h(suggested_h(cloud));
  params.projection.surface = surface;
  params.projection.outliers = outliers;
  Aabb sphere_box;  // the sphere's, not the strays'
  sphere_box.grow(vec3(-1.0f));
  sphere_box.grow(vec3(1.0f));
  return against_sphere(render_at_160(cloud, params, backend, sphere_box, 30, 20), Sphere{}, 0.05f);
}

}  // namespace pss::test
