#include "pss/io/exr.hpp"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfIO.h>
#include <ImfOutputFile.h>
#include <half.h>

#include <exception>
#include <string>
#include <vector>

#include "pss/core/error.hpp"
#include "pss/io/output_file.hpp"

namespace pss {
namespace {

// OpenEXR writes through its own stream type; this one hands the bytes to OutputFile, which
// makes the file appear atomically. OpenEXR seeks back to fill in the line offsets.
class OutputFileStream : public Imf::OStream {
 public:
  explicit OutputFileStream(OutputFile& file, const std::string& name) : Imf::OStream(name.c_str()), out_(file.stream()) {}
  void write(const char c[], int n) override {
    if (!out_.write(c, n)) throw Error("write failed");
  }
  uint64_t tellp() override { return std::uint64_t(out_.tellp()); }
  void seekp(uint64_t pos) override {
    if (!out_.seekp(std::streamoff(pos))) throw Error("seek failed");
  }

 private:
  std::ostream& out_;
};

}  // namespace

void write_exr(const std::filesystem::path& path, const ExrLayers& layers) {
  const std::size_t n = std::size_t(layers.width) * std::size_t(layers.height);
  if (layers.width <= 0 || layers.height <= 0 || layers.rgba.size() != n || layers.depth.size() != n ||
      layers.normal.size() != n)
    throw file_error(path, "cannot write: the layers are not all " + std::to_string(layers.width) + "x" +
                               std::to_string(layers.height));
  // OpenEXR reads strided pixels: the colour as half, one array per component.
  std::vector<half> rgba(4 * n);
  for (std::size_t i = 0; i < n; ++i)
    for (int c = 0; c < 4; ++c) rgba[4 * i + c] = half(layers.rgba[i][c]);

  Imf::Header header(layers.width, layers.height);
  Imf::FrameBuffer buffer;
  const auto add = [&](const char* name, Imf::PixelType type, const void* first, std::size_t x_stride) {
    header.channels().insert(name, Imf::Channel(type));
    buffer.insert(name, Imf::Slice(type, const_cast<char*>(static_cast<const char*>(first)), x_stride,
                                   x_stride * std::size_t(layers.width)));
  };
  const char* colour[] = {"R", "G", "B", "A"};
  for (int c = 0; c < 4; ++c) add(colour[c], Imf::HALF, &rgba[std::size_t(c)], 4 * sizeof(half));
  add("Z", Imf::FLOAT, layers.depth.data(), sizeof(float));
  const char* normal[] = {"N.X", "N.Y", "N.Z"};
  for (int c = 0; c < 3; ++c)
    add(normal[c], Imf::FLOAT, reinterpret_cast<const float*>(layers.normal.data()) + c, sizeof(vec3));

  OutputFile file(path);
  try {
    OutputFileStream stream(file, path.string());
    Imf::OutputFile exr(stream, header, 1);
    exr.setFrameBuffer(buffer);
    exr.writePixels(layers.height);
  } catch (const std::exception& e) {  // Iex::BaseExc and our stream's Error
    throw file_error(path, "cannot write: " + one_line(e.what()));
  }
  file.commit();
}

}  // namespace pss
