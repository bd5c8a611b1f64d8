// One rendered frame: per-pixel hits, the image and the count of secondary rays. The frame
// driver that makes it from any surface finder is render/render_frame.hpp.
#pragma once

#include <cstdint>
#include <vector>

#include "pss/render/camera.hpp"
#include "pss/render/image.hpp"
#include "pss/render/trace.hpp"

namespace pss {

struct RenderedFrame {
  Camera camera;
  std::vector<Hit> hits;  // per pixel, row-major from the top row
  Image image;
  std::int64_t secondary_rays = 0;
};

}  // namespace pss
