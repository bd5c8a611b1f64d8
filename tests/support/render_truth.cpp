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

RenderTruth render_sphere(const PointCloud& cloud, SurfaceOperator surface, OutlierPolicy outliers, Backend backend) {
  RayPssParams params = RayPssParams::from_h(suggested_h(cloud));
  params.projection.surface = surface;
  params.projection.outliers = outliers;
  Stats stats;
  const PreparedCloud prepared(cloud, params, backend, stats);
  CameraSettings view;
  view.width = view.height = 160;
  view.azimuth_deg = 30;
  view.elevation_deg = 20;
  Aabb sphere_box;  // the sphere's, not the strays'
  sphere_box.grow(vec3(-1.0f));
  sphere_box.grow(vec3(1.0f));
  const Camera camera = Camera::framing(sphere_box, view);
  const RenderedFrame frame =
      render_cloud(prepared, camera, TraceSettings::for_camera(camera, false, false), backend, stats);
  return against_sphere(frame, Sphere{}, 0.05f);
}

}  // namespace pss::test
