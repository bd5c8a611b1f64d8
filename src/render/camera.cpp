#include "pss/render/camera.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace pss {

Camera Camera::framing(const Aabb& box, const CameraSettings& s) {
  constexpr float degree = std::numbers::pi_v<float> / 180.0f;
  const vec3 center = box.empty() ? vec3(0.0f) : box.center();
  float radius = box.empty() ? 0.0f : 0.5f * glm::length(box.extent());
  if (!(radius > 0)) radius = 1.0f;

  Camera c;
  c.width = s.width;
  c.height = s.height;
  c.tan_half_fov = std::tan(0.5f * s.fov_deg * degree);
  // The sphere touches the narrower field of view: sin(half angle) = radius / distance.
  const float tan_half_narrow = c.tan_half_fov * std::min(1.0f, float(s.width) / float(s.height));
  const float half_narrow = std::atan(tan_half_narrow);
  const float distance = radius / std::sin(half_narrow);

  const float az = s.azimuth_deg * degree, el = s.elevation_deg * degree;
  const vec3 toward_eye(std::sin(az) * std::cos(el), std::sin(el), std::cos(az) * std::cos(el));
  c.eye = center + distance * toward_eye;
  c.forward = -toward_eye;
  // The horizontal axis depends on the azimuth alone, so the basis stays defined looking
  // straight down or up.
  c.right = vec3(std::cos(az), 0.0f, -std::sin(az));
  c.up = glm::cross(c.right, c.forward);
  return c;
}

}  // namespace pss
