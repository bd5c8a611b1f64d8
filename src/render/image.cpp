#include "pss/render/image.hpp"

#include <array>
#include <cmath>

#include "pss/io/image_8bit.hpp"

namespace pss {

std::uint8_t linear_to_srgb8(float linear) {
  const float c = std::isfinite(linear) ? std::fmin(std::fmax(linear, 0.0f), 1.0f) : 0.0f;
  const float s = c <= 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
  return std::uint8_t(std::lround(s * 255.0f));
}

float srgb8_to_linear(std::uint8_t srgb) {
  static const std::array<float, 256> table = [] {
    std::array<float, 256> t{};
    for (int i = 0; i < 256; ++i) {
      const double s = i / 255.0;
      t[std::size_t(i)] = float(s <= 0.04045 ? s / 12.92 : std::pow((s + 0.055) / 1.055, 2.4));
    }
    return t;
  }();
  return table[srgb];
}

std::vector<std::uint8_t> to_srgb8(const Image& image) {
  std::vector<std::uint8_t> rgb(image.pixels.size() * 3);
  for (std::size_t i = 0; i < image.pixels.size(); ++i)
    for (int c = 0; c < 3; ++c) rgb[3 * i + c] = linear_to_srgb8(image.pixels[i][c]);
  return rgb;
}

void write_png(const std::filesystem::path& path, const Image& image) {
  write_png(path, image.width, image.height, to_srgb8(image));
}

}  // namespace pss
