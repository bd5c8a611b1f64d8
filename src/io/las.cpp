#include "pss/io/las.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <string>

#include "bytes.hpp"
#include "color.hpp"
#include "file_window.hpp"
#include "pss/core/error.hpp"
#include "pss/io/output_file.hpp"

namespace pss {
namespace {

constexpr bool kSwap = std::endian::native != std::endian::little;  // LAS is little-endian

// The public header's size up to LAS 1.3's fields, and with 1.4's 64-bit point counts.
constexpr std::size_t kHeaderBefore14 = 227, kHeader14 = 375;

// Each point data record format's length in bytes and where its RGB begins (0: none).
struct RecordFormat {
  std::uint64_t length, rgb;
};
constexpr RecordFormat kFormats[] = {{20, 0},  {28, 0},  {26, 20}, {34, 28}, {57, 0}, {63, 28},
                                     {30, 0},  {36, 30}, {38, 30}, {59, 0},  {67, 30}};

// A little-endian value at a byte offset the caller has checked.
template <class T>
T get(std::string_view bytes, std::uint64_t at) {
  return io::load<T>(bytes.data() + at, kSwap);
}

}  // namespace

PointCloud read_las(const std::filesystem::path& path) {
  io::FileWindow data(path);
  data.fill(std::size_t(std::min<std::uint64_t>(kHeader14, data.size())));
  const std::string_view file = data.view();  // the header's bytes; data.size() is the file's
  if (!file.starts_with("LASF")) throw file_error(path, "not a LAS file (no 'LASF' signature)");
  if (file.size() < kHeaderBefore14)
    throw file_error(path, "truncated: " + std::to_string(file.size()) + " bytes, less than a LAS header");
  const int major = get<std::uint8_t>(file, 24), minor = get<std::uint8_t>(file, 25);
  if (major != 1 || minor > 4)
    throw file_error(path, "unsupported LAS version " + std::to_string(major) + "." + std::to_string(minor) +
                               " (1.0 to 1.4 are read)");
  const std::uint64_t header_size = get<std::uint16_t>(file, 94), data_offset = get<std::uint32_t>(file, 96);
  const unsigned format = get<std::uint8_t>(file, 104);
  const std::uint64_t record_length = get<std::uint16_t>(file, 105);
  const std::size_t needed_header = minor >= 4 ? kHeader14 : kHeaderBefore14;
  if (header_size < needed_header || header_size > data.size())
    throw file_error(path, "header size " + std::to_string(header_size) + " is not between LAS 1." +
                               std::to_string(minor) + "'s " + std::to_string(needed_header) + " and the file's " +
                               std::to_string(data.size()) + " bytes");
  // LAZ sets the top bits of the format (LASzip's convention).
  if (format & 0xC0) throw file_error(path, "compressed LAS (LAZ) is not supported; decompress it to .las first (laszip, PDAL)");
  if (format > 10) throw file_error(path, "unknown point data record format " + std::to_string(format));
  const RecordFormat record = kFormats[format];
  if (record_length < record.length)
    throw file_error(path, "point records of " + std::to_string(record_length) + " bytes are shorter than format " +
                               std::to_string(format) + "'s " + std::to_string(record.length));
  if (data_offset < header_size || data_offset > data.size())
    throw file_error(path, "offset to point data " + std::to_string(data_offset) + " is not between the header's " +
                               std::to_string(header_size) + " bytes and the file's " + std::to_string(data.size()));

  std::uint64_t points = get<std::uint32_t>(file, 107);
  if (minor >= 4) {
    // 1.4 keeps the legacy count 0 for formats 6-10 and where the count passes 32 bits.
    const std::uint64_t points64 = get<std::uint64_t>(file, 247);
    if (points != 0 && points64 != 0 && points != points64)
      throw file_error(path, "the legacy point count " + std::to_string(points) + " differs from the 64-bit one " +
                                 std::to_string(points64));
    points = std::max(points, points64);
  }
  if (points == 0) throw file_error(path, "no points");
  const std::uint64_t available = data.size() - data_offset;
  if (points > available / record_length)
    throw file_error(path, "truncated: " + std::to_string(points) + " points of " + std::to_string(record_length) +
                               " bytes need more than the " + std::to_string(available) + " bytes after the header");

  glm::dvec3 scale, offset;
  for (int k = 0; k < 3; ++k) {
    scale[k] = get<double>(file, 131 + 8 * k);
    offset[k] = get<double>(file, 155 + 8 * k);
    if (!(std::isfinite(scale[k]) && scale[k] != 0 && std::isfinite(offset[k])))
      throw file_error(path, "invalid scale " + format_number(scale[k]) + " or offset " + format_number(offset[k]) +
                                 " of axis " + "xyz"[k]);
  }
  // The records front to back: the attributes every record format has, kept as scalar
  // properties for outputs to carry (the intensity, bytes 12-13, and the ASPRS class, bits
  // 0-4 of byte 15 in formats 0-5, whose upper bits are flags, and byte 16 in formats 6-10),
  // and the colours' 16-bit channels until the brightest says how they scale.
  PointCloud cloud;
  std::vector<glm::dvec3> world;
  world.reserve(points);
  ScalarProperty intensity{"intensity", ScalarType::uint16, {}};
  ScalarProperty classification{"classification", ScalarType::uint8, {}};
  intensity.values.reserve(points);
  classification.values.reserve(points);
  std::vector<std::array<std::uint16_t, 3>> channels;
  if (record.rgb != 0) channels.reserve(points);
  data.skip(data_offset);
  for (std::uint64_t i = 0; i < points; ++i) {
    if (!data.fill(record_length))  // the file shrank while it was read
      throw file_error(path, "truncated: expected " + std::to_string(points) + " points, read " + std::to_string(i));
    const std::string_view r = data.view();
    const glm::dvec3 integer(get<std::int32_t>(r, 0), get<std::int32_t>(r, 4), get<std::int32_t>(r, 8));
    world.push_back(integer * scale + offset);
    if (!is_finite(vec3(world.back())))
      throw file_error(path, "point " + std::to_string(i) + " lies beyond float's range");
    intensity.values.push_back(get<std::uint16_t>(r, 12));
    classification.values.push_back(format <= 5 ? get<std::uint8_t>(r, 15) & 0x1F : get<std::uint8_t>(r, 16));
    if (record.rgb != 0)
      channels.push_back({get<std::uint16_t>(r, record.rgb), get<std::uint16_t>(r, record.rgb + 2),
                          get<std::uint16_t>(r, record.rgb + 4)});
    data.consume(record_length);
  }
  set_world_positions(cloud, world);
  cloud.scalars = {std::move(intensity), std::move(classification)};
  if (record.rgb != 0) {
    std::uint16_t brightest = 0;
    for (const auto& rgb : channels)
      for (const std::uint16_t c : rgb) brightest = std::max(brightest, c);
    cloud.colors.resize(points);
    for (std::uint64_t i = 0; i < points; ++i)
      for (int c = 0; c < 3; ++c)
        cloud.colors[i][c] = brightest <= 255 ? std::uint8_t(channels[i][c]) : io::channel_from_16bit(channels[i][c]);
  }
  return cloud;
}

}  // namespace pss
