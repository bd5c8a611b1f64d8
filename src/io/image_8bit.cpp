#include "pss/io/image_8bit.hpp"

#include <string>

#include "pss/core/error.hpp"
#include "pss/io/output_file.hpp"

// Header-only stb, compiled here alone: static keeps its symbols out of other objects
// (no clash with a libstb elsewhere), no-stdio because output goes through OutputFile.
#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STB_IMAGE_WRITE_STATIC
#define STBI_WRITE_NO_STDIO
#include <stb/stb_image_write.h>

namespace pss {
namespace {

void check_size(const std::filesystem::path& path, int width, int height, std::size_t bytes, int channels) {
  if (width <= 0 || height <= 0 ||
      bytes != static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * std::size_t(channels))
    throw file_error(path, "cannot write: " + std::to_string(bytes) + " bytes are not a " + std::to_string(width) +
                               "x" + std::to_string(height) + (channels == 4 ? " RGBA" : " RGB") + " image");
}

// stb encodes in memory; the bytes then go through OutputFile, so the file appears atomically.
template <class Encode>
void write_encoded(const std::filesystem::path& path, const char* format, Encode encode) {
  std::string bytes;  // GCC 12 warns falsely of an overflow with vector::insert inlined into stb's JPEG code
  const auto append = [](void* context, void* data, int size) {
    static_cast<std::string*>(context)->append(static_cast<const char*>(data), std::size_t(size));
  };
  if (!encode(append, &bytes)) throw file_error(path, std::string("cannot write: ") + format + " encoding failed");
  OutputFile file(path);
  file.stream().write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  file.commit();
}

}  // namespace

void write_png(const std::filesystem::path& path, int width, int height, std::span<const std::uint8_t> pixels,
               int channels) {
  check_size(path, width, height, pixels.size(), channels);
  write_encoded(path, "PNG", [&](stbi_write_func* append, void* context) {
    return stbi_write_png_to_func(append, context, width, height, channels, pixels.data(), width * channels);
  });
}

void write_jpeg(const std::filesystem::path& path, int width, int height, std::span<const std::uint8_t> rgb,
                int quality) {
  check_size(path, width, height, rgb.size(), 3);
  write_encoded(path, "JPEG", [&](stbi_write_func* append, void* context) {
    return stbi_write_jpg_to_func(append, context, width, height, 3, rgb.data(), quality);
  });
}

}  // namespace pss
