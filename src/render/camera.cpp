#include "pss/render/camera.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "pss/core/error.hpp"
#include "pss/core/text.hpp"

namespace pss {

namespace {

bool finite(vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

void check_range(const char* what, double x, double lo, double hi) {
  if (!(x >= lo && x <= hi))
    throw Error(std::string(what) + " must be from " + format_number(lo) + " to " + format_number(hi) + " (got " +
                format_number(x) + ")");
}

}  // namespace

void validate(const CameraSettings& s) {
  if (s.width < 1 || s.height < 1 || s.width > kMaxImageSide || s.height > kMaxImageSide)
    throw Error("the image's width and height must be from 1 to " + std::to_string(kMaxImageSide) + " (got " +
                std::to_string(s.width) + "x" + std::to_string(s.height) + ")");
  if (static_cast<long long>(s.width) * s.height > kMaxImagePixels)
    throw Error("the image may have at most " + std::to_string(kMaxImagePixels) + " pixels, e.g. 8192x8192 (got " +
                std::to_string(s.width) + "x" + std::to_string(s.height) + ")");
  if (!std::isfinite(s.azimuth_deg)) throw Error("the azimuth must be a finite number of degrees");
  check_range("the elevation", s.elevation_deg, -90, 90);
  check_range("the field of view", s.fov_deg, kMinFovDeg, kMaxFovDeg);
  if (s.has_look_at && !(glm::length(s.look_at) < 1e30))  // false for NaN and infinity too
    throw Error("the look-at point must be three finite numbers, less than 1e30 from zero");
  if (!finite(s.up) || !(glm::length(s.up) > 0)) throw Error("up must be a non-zero direction of three finite numbers");
  if (!(s.distance >= 0 && std::isfinite(s.distance)))
    throw Error("the distance must be a finite positive number (got " + format_number(s.distance) + ")");
  check_range("the zoom", s.zoom, kMinZoom, kMaxZoom);
  check_range("the roll", s.roll_deg, -kMaxRollDeg, kMaxRollDeg);
}

Camera Camera::framing(const Aabb& box, const CameraSettings& s) {
  constexpr float degree = std::numbers::pi_v<float> / 180.0f;
  const vec3 center = s.has_look_at ? vec3(s.look_at) : box.empty() ? vec3(0.0f) : box.center();
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
  // straight down or up, about any up (an aerial scan seen from above with --up 0,0,1).
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
