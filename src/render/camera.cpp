#include "pss/render/camera.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace pss {

Camera Camera::framing(const Aabb& box, const CameraSettings& s) {
  constexpr float degree = std::numbers::pi_v<float> / 180.0f;
  const vec3 center = s.has_look_at ? s.look_at : box.empty() ? vec3(0.0f) : box.center();
  float radius = box.empty() ? 0.0f : 0.5f * glm::length(box.extent());
  if (!(radius > 0)) radius = 1.0f;

  Camera c;
  c.width = s.width;
  c.height = s.height;
  c.tan_half_fov = std::tan(0.5f * s.fov_deg * degree);
  // The sphere touches the narrower field of view: sin(half angle) = radius / distance.
  const float tan_half_narrow = c.tan_half_fov * std::min(1.0f, float(s.width) / float(s.height));
  const float half_narrow = std::atan(tan_half_narrow);
  const float distance = (s.distance > 0 ? s.distance : radius / std::sin(half_narrow)) / s.zoom;

  // The orbit's frame: `up`, and front and side across it (x, y, z for the default y up).
  const vec3 up = glm::normalize(s.up);
  vec3 front(0, 0, 1), side(1, 0, 0);
  if (up != vec3(0, 1, 0)) {
    const vec3 z(0, 0, 1), minus_y(0, -1, 0);
    const vec3 toward = std::abs(glm::dot(z, up)) < 0.9f ? z : minus_y;
    front = glm::normalize(toward - glm::dot(toward, up) * up);
    side = glm::cross(up, front);
  }
  const float az = s.azimuth_deg * degree, el = s.elevation_deg * degree;
  const vec3 toward_eye = std::sin(az) * std::cos(el) * side + std::sin(el) * up + std::cos(az) * std::cos(el) * front;
  c.eye = center + distance * toward_eye;
  c.forward = -toward_eye;
  // The horizontal axis depends on the azimuth alone, so the basis stays defined looking
  // straight down or up.
  c.right = std::cos(az) * side - std::sin(az) * front;
  c.up = glm::cross(c.right, c.forward);
  if (s.roll_deg != 0) {
    const float r = s.roll_deg * degree;
    const vec3 right = c.right;
    c.right = std::cos(r) * right + std::sin(r) * c.up;
    c.up = std::cos(r) * c.up - std::sin(r) * right;
  }
  return c;
}

}  // namespace pss
