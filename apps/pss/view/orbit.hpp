// The viewer's camera: the documented default view (Camera::framing) turned by azimuth and
// elevation, moved toward its target by a zoom factor and sideways by a pan, so that the
// view a user finds is the one `pss render --view AZ,EL --fov F` gives at zoom 1, no pan.
#pragma once

#include "pss/render/camera.hpp"

namespace pss::app::view {

struct Orbit {
  float azimuth = 0, elevation = 0;  // degrees, elevation in [−89.9, 89.9] while dragging
  float fov = 35;                    // vertical, degrees
  float zoom = 1;                    // > 1: closer
  vec2 pan{0.0f};                    // in units of the framing distance, along right and up

  Camera camera(const Aabb& bounds, int width, int height) const {
    CameraSettings s;
    s.width = width;
    s.height = height;
    s.azimuth_deg = azimuth;
    s.elevation_deg = elevation;
    s.fov_deg = fov;
    Camera c = Camera::framing(bounds, s);
    if (zoom == 1 && pan == vec2(0.0f)) return c;  // exactly pss render's camera
    const vec3 target = bounds.empty() ? vec3(0.0f) : bounds.center();
    const float distance = glm::length(c.eye - target);
    c.eye = target + (c.eye - target) / zoom + distance * (pan.x * c.right + pan.y * c.up);
    return c;
  }
};

}  // namespace pss::app::view
