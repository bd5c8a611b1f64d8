// OpenEXR output of a rendered frame: linear colour with alpha, and the depth and normal
// layers that compositing and relighting need.
#pragma once

#include <filesystem>
#include <span>

#include "pss/core/types.hpp"

namespace pss {

struct ExrLayers {
  int width = 0, height = 0;     // every span holds width * height values, rows top to bottom
  std::span<const vec4> rgba;    // R G B A (half): linear, premultiplied by A as OpenEXR defines
  std::span<const float> depth;  // Z (float)
  std::span<const vec3> normal;  // N.X N.Y N.Z (float)
};

// Scan lines, ZIP compressed. Written atomically (OutputFile); OpenEXR's errors become
// file_error(path, "cannot write: ...").
void write_exr(const std::filesystem::path& path, const ExrLayers& layers);

}  // namespace pss
