// One rendered frame: per-pixel hits, the image and the count of secondary rays. The frame
// driver that makes it from any surface finder is render/render_frame.hpp.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/ext/vector_double3.hpp>

#include "pss/render/camera.hpp"
#include "pss/render/image.hpp"
#include "pss/render/trace.hpp"

namespace pss {

struct RenderedFrame {
  Camera camera;
  std::vector<Hit> hits;  // per pixel, row-major from the top row
  Image image;
  std::int64_t secondary_rays = 0;
  glm::dvec3 origin{0.0};  // the world position of the frame's zero (a cloud's origin, cloud.hpp)
};

}  // namespace pss
