#include "pss/io/png.hpp"

#include <string>
#include <vector>

#include "pss/core/error.hpp"
#include "pss/io/output_file.hpp"

// Header-only stb, compiled here alone: static keeps its symbols out of other objects
// (no clash with a libstb elsewhere), no-stdio because output goes through OutputFile.
#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STB_IMAGE_WRITE_STATIC
#define STBI_WRITE_NO_STDIO
#include <stb/stb_image_write.h>

namespace pss {

void write_png(const std::filesystem::path& path, int width, int height,
               std::span<const std::uint8_t> rgb) {
  if (width <= 0 || height <= 0 ||
      rgb.size() != static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 3)
    throw file_error(path, "cannot write: " + std::to_string(rgb.size()) +
                               " bytes are not a " + std::to_string(width) + "x" +
                               std::to_string(height) + " RGB image");
  // Encode in memory, then write through OutputFile so that the file appears atomically.
  std::vector<char> png;
  const auto append = [](void* context, void* data, int size) {
    auto& out = *static_cast<std::vector<char>*>(context);
    const char* bytes = static_cast<const char*>(data);
    out.insert(out.end(), bytes, bytes + size);
  };
  if (!stbi_write_png_to_func(append, &png, width, height, 3, rgb.data(), width * 3))
    throw file_error(path, "cannot write: PNG encoding failed");
  OutputFile file(path);
  file.stream().write(png.data(), static_cast<std::streamsize>(png.size()));
  file.commit();
}

}  // namespace pss
