#include "support/output_readers.hpp"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <sstream>

#define STB_IMAGE_IMPLEMENTATION
#define STB_IMAGE_STATIC
#include <stb/stb_image.h>

namespace pss::test {

Image8 read_image8(const std::filesystem::path& path) {
  Image8 image;
  unsigned char* data = stbi_load(path.c_str(), &image.width, &image.height, &image.channels, 0);
  if (!data) return Image8{};
  image.bytes.assign(data, data + std::size_t(image.width) * image.height * image.channels);
  stbi_image_free(data);
  return image;
}

ExrImage read_exr(const std::filesystem::path& path) {
  Imf::InputFile file(path.c_str());
  const Imath::Box2i window = file.header().dataWindow();
  ExrImage image;
  image.width = window.max.x - window.min.x + 1;
  image.height = window.max.y - window.min.y + 1;
  Imf::FrameBuffer buffer;
  for (auto c = file.header().channels().begin(); c != file.header().channels().end(); ++c)
    image.channels[c.name()].resize(std::size_t(image.width) * image.height);
  for (auto& [name, values] : image.channels)
    buffer.insert(name, Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(values.data()), sizeof(float),
                                   sizeof(float) * std::size_t(image.width)));
  file.setFrameBuffer(buffer);
  file.readPixels(window.min.y, window.max.y);
  return image;
}

PlyColumns read_ply_columns(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  PlyColumns ply;
  std::vector<std::pair<std::string, std::string>> properties;  // type, name
  std::size_t count = 0;
  for (std::string line; std::getline(in, line);) {
    ply.header.push_back(line);
    std::istringstream words(line);
    std::string word, type, name;
    words >> word;
    if (word == "element") words >> name >> count;
    if (word == "property" && words >> type >> name) properties.emplace_back(type, name);
    if (word == "end_header") break;
  }
  for (std::size_t i = 0; i < count; ++i)
    for (const auto& [type, name] : properties) {
      char bytes[8];
      if (type == "uchar") {
        in.read(bytes, 1);
        ply.columns[name].push_back(std::uint8_t(bytes[0]));
      } else if (type == "double") {
        double d;
        in.read(bytes, 8);
        std::memcpy(&d, bytes, 8);
        ply.columns[name].push_back(d);
      } else if (type == "float") {
        float f;
        in.read(bytes, 4);
        std::memcpy(&f, bytes, 4);
        ply.columns[name].push_back(f);
      } else {
        std::int32_t v;
        in.read(bytes, 4);
        std::memcpy(&v, bytes, 4);
        ply.columns[name].push_back(v);
      }
    }
  return ply;
}

ProjectedApart compare_projected(const PlyColumns& a, const PlyColumns& b, double distance) {
  ProjectedApart c;
  const std::size_t n = a.columns.at("x").size();
  for (std::size_t i = 0; i < n; ++i) {
    const auto at = [&](const PlyColumns& p, const char* name) { return p.columns.at(name).at(i); };
    c.apart += std::hypot(at(a, "x") - at(b, "x"), at(a, "y") - at(b, "y"), at(a, "z") - at(b, "z")) > distance;
    c.facing_apart += at(a, "nx") * at(b, "nx") + at(a, "ny") * at(b, "ny") + at(a, "nz") * at(b, "nz") < 0;
    c.status_differ += at(a, "status") != at(b, "status");
  }
  return c;
}

}  // namespace pss::test
