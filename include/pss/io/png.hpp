// PNG output for rendered images.
#pragma once

#include <cstdint>
#include <filesystem>
#include <span>

namespace pss {

// rgb: width * height * 3 bytes, rows top to bottom. Written atomically (OutputFile).
void write_png(const std::filesystem::path& path, int width, int height,
               std::span<const std::uint8_t> rgb);

}  // namespace pss
