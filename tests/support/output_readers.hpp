// Reading back what pss writes with each format's own library (stb_image, OpenEXR) or, for
// the PLY properties pss's reader skips, a parser of the few lines pss's writer emits.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace pss::test {

// PNG or JPEG through stb_image: width, height, channels as stored, bytes row by row from the
// top. channels 0 when the file does not decode.
struct Image8 {
  int width = 0, height = 0, channels = 0;
  std::vector<std::uint8_t> bytes;
  std::uint8_t at(int x, int y, int c) const { return bytes[(std::size_t(y) * width + x) * channels + c]; }
};
Image8 read_image8(const std::filesystem::path& path);

// Every channel of a scan-line EXR as float, by name (OpenEXR converts half to float).
struct ExrImage {
  int width = 0, height = 0;
  std::map<std::string, std::vector<float>> channels;
  float at(const std::string& name, int x, int y) const { return channels.at(name)[std::size_t(y) * width + x]; }
};
ExrImage read_exr(const std::filesystem::path& path);

// A binary little-endian PLY's vertex properties (float, double, int or uchar), by name, as double.
struct PlyColumns {
  std::vector<std::string> header;  // the header's lines, "ply" to "end_header"
  std::map<std::string, std::vector<double>> columns;
};
PlyColumns read_ply_columns(const std::filesystem::path& path);

// Two outputs of pss project, point by point: how many lie farther apart than `distance`,
// whose normals face apart, whose status differs.
struct ProjectedApart {
  std::size_t apart = 0, facing_apart = 0, status_differ = 0;
};
ProjectedApart compare_projected(const PlyColumns& a, const PlyColumns& b, double distance);

}  // namespace pss::test
