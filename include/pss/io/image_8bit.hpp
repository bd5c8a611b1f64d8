// 8-bit images (stb_image_write): PNG with or without alpha, and JPEG.
#pragma once

#include <cstdint>
#include <filesystem>
#include <span>

namespace pss {

// pixels: width * height * channels bytes, rows top to bottom; 3 channels (RGB) or 4 (RGBA,
// straight alpha as PNG defines it). Written atomically (OutputFile).
void write_png(const std::filesystem::path& path, int width, int height, std::span<const std::uint8_t> pixels,
               int channels = 3);

// rgb: width * height * 3 bytes, rows top to bottom; quality 1..100. Written atomically.
void write_jpeg(const std::filesystem::path& path, int width, int height, std::span<const std::uint8_t> rgb,
                int quality);

}  // namespace pss
