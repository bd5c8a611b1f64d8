// A rendered image in linear float RGB, and its sRGB 8-bit PNG.
#pragma once

#include <cstdint>
#include <filesystem>
#include <vector>

#include "pss/core/types.hpp"

namespace pss {

struct Image {
  int width = 0, height = 0;
  std::vector<vec3> pixels;  // linear RGB, row 0 at the top

  Image() = default;
  Image(int w, int h) : width(w), height(h), pixels(std::size_t(w) * std::size_t(h), vec3(0.0f)) {}
  vec3& at(int x, int y) { return pixels[std::size_t(y) * width + x]; }
  const vec3& at(int x, int y) const { return pixels[std::size_t(y) * width + x]; }
};

// The sRGB transfer function (IEC 61966-2-1), clamped to [0, 1], rounded to 8 bits.
std::uint8_t linear_to_srgb8(float linear);
// Its inverse for 8-bit input, exact to float: what an sRGB colour is in linear light.
float srgb8_to_linear(std::uint8_t srgb);
std::vector<std::uint8_t> to_srgb8(const Image& image);

// Written atomically through write_png.
void write_png(const std::filesystem::path& path, const Image& image);

}  // namespace pss
