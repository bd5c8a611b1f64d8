// The default camera: where it stands for a view, and that it frames the whole object.
#include <gtest/gtest.h>

#include "pss/render/camera.hpp"

namespace pss {
namespace {

// Pixel coordinates (continuous) where a world point appears.
vec2 project(const Camera& c, vec3 p) {
  const vec3 d = p - c.eye;
  const float z = glm::dot(d, c.forward);
  const float aspect = float(c.width) / float(c.height);
  const float x = glm::dot(d, c.right) / (z * c.tan_half_fov * aspect);
  const float y = glm::dot(d, c.up) / (z * c.tan_half_fov);
  return vec2((x + 1) * 0.5f * c.width, (1 - y) * 0.5f * c.height);
}

Aabb box() {
  Aabb b;
  b.grow(vec3(-1, 2, 0));
  b.grow(vec3(3, 4, 0.5f));
  return b;
}

TEST(Camera, DefaultViewLooksAlongMinusZFromPlusZ) {
  const Camera c = Camera::framing(box(), CameraSettings{});
  const vec3 center = box().center();
  EXPECT_NEAR(c.eye.x, center.x, 1e-5f);
  EXPECT_NEAR(c.eye.y, center.y, 1e-5f);
  EXPECT_GT(c.eye.z, center.z);
  EXPECT_NEAR(glm::dot(c.forward, vec3(0, 0, -1)), 1.0f, 1e-6f);
  EXPECT_NEAR(glm::dot(c.up, vec3(0, 1, 0)), 1.0f, 1e-6f);
  EXPECT_NEAR(glm::dot(c.right, vec3(1, 0, 0)), 1.0f, 1e-6f);
}

TEST(Camera, OrbitsTheCentre) {
  const vec3 center = box().center();
  CameraSettings s;
  s.azimuth_deg = 90;
  const Camera side = Camera::framing(box(), s);
  EXPECT_GT(side.eye.x - center.x, 0);  // positive azimuth turns toward +x
  EXPECT_NEAR(side.eye.z, center.z, 1e-4f);
  s = CameraSettings{};
  s.elevation_deg = 90;  // straight down: the basis stays orthonormal and finite
  const Camera top = Camera::framing(box(), s);
  EXPECT_GT(top.eye.y, center.y);
  EXPECT_NEAR(glm::length(top.up), 1.0f, 1e-5f);
  EXPECT_NEAR(glm::dot(top.up, top.forward), 0.0f, 1e-5f);
  EXPECT_NEAR(glm::length(top.eye - center), glm::length(Camera::framing(box(), CameraSettings{}).eye - center), 1e-4f);
}

TEST(Camera, FramesTheBoundingSphereForAnyAspect) {
  for (const auto& [w, h] : {std::pair{64, 64}, std::pair{160, 90}, std::pair{90, 160}}) {
    CameraSettings s;
    s.width = w;
    s.height = h;
    s.azimuth_deg = 30;
    s.elevation_deg = 20;
    const Camera c = Camera::framing(box(), s);
    const vec2 mid = project(c, box().center());
    EXPECT_NEAR(mid.x, 0.5f * w, 1e-3f * w);
    EXPECT_NEAR(mid.y, 0.5f * h, 1e-3f * h);
    for (int corner = 0; corner < 8; ++corner) {
      const vec3 p(corner & 1 ? box().hi.x : box().lo.x, corner & 2 ? box().hi.y : box().lo.y,
                   corner & 4 ? box().hi.z : box().lo.z);
      const vec2 q = project(c, p);
      EXPECT_GE(q.x, 0.0f);
      EXPECT_LE(q.x, float(w));
      EXPECT_GE(q.y, 0.0f);
      EXPECT_LE(q.y, float(h));
    }
  }
}

TEST(Camera, PrimaryRaysGoThroughPixelCentres) {
  CameraSettings s;
  s.width = 33;
  s.height = 17;
  const Camera c = Camera::framing(box(), s);
  const Ray centre = c.primary_ray(16, 8);
  EXPECT_NEAR(glm::dot(centre.dir, c.forward), 1.0f, 1e-6f);
  const Ray corner = c.primary_ray(0, 0);  // top left
  EXPECT_LT(glm::dot(corner.dir, c.right), 0);
  EXPECT_GT(glm::dot(corner.dir, c.up), 0);
  EXPECT_NEAR(glm::length(corner.dir), 1.0f, 1e-6f);
}

TEST(Camera, DegenerateBoxIsFramedAsAUnitSphere) {
  Aabb point;
  point.grow(vec3(1, 2, 3));
  const Camera c = Camera::framing(point, CameraSettings{});
  EXPECT_TRUE(is_finite(c.eye));
  EXPECT_GT(glm::length(c.eye - vec3(1, 2, 3)), 1.0f);
}

}  // namespace
}  // namespace pss
