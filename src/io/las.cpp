#include "pss/io/las.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <memory>
#include <string>

#include "bytes.hpp"
#include "color.hpp"
#include "file_window.hpp"
#include "point_streams.hpp"
#include "pss/core/error.hpp"

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

// The header's facts about the points, checked against the file's size.
struct LasLayout {
  unsigned format;
  RecordFormat record;
  std::uint64_t record_length, points;
  glm::dvec3 scale, offset;
};

// Reads and checks the header, and leaves `data` at the first point record.
LasLayout read_las_header(const std::filesystem::path& path, io::FileWindow& data) {
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
  data.skip(data_offset);
  return {format, record, record_length, points, scale, offset};
}

// The points of a LAS file, a record at a time. Colours: the brightest channel of the whole
// file says whether they are 8-bit values in 16-bit fields or 16-bit ones, or none at all
// where every channel is 0 (an aerial scan's format with RGB fields that nothing filled: its
// colours would render black), so a file with colours is read twice, the first time for them alone.
class LasStream final : public PointStream {
 public:
  explicit LasStream(const std::filesystem::path& path) : path_(path), data_(path), las_(read_las_header(path, data_)) {
    if (las_.record.rgb == 0) return;
    io::FileWindow first(path);
    read_las_header(path, first);
    for (std::uint64_t i = 0; i < las_.points && first.fill(las_.record_length); ++i) {
      for (int c = 0; c < 3; ++c)
        brightest_ = std::max(brightest_, get<std::uint16_t>(first.view(), las_.record.rgb + 2 * std::uint64_t(c)));
      first.consume(las_.record_length);
    }
  }

  std::uint64_t declared_count() const override { return las_.points; }

  // The attributes every record format has are kept as scalar properties for outputs to
  // carry: the intensity (bytes 12-13) and the ASPRS class, bits 0-4 of byte 15 in formats
  // 0-5 (its upper bits are flags) and byte 16 in formats 6-10.
  std::size_t read(PointPart& part, std::size_t most) override {
    if (part.scalars.empty())
      part.scalars = {{"intensity", ScalarType::uint16, {}}, {"classification", ScalarType::uint8, {}}};
    const std::uint64_t end = std::min<std::uint64_t>(las_.points, next_ + most), begin = next_;
    for (std::uint64_t i = begin; i < end; ++i) {
      if (!data_.fill(las_.record_length))  // the file shrank while it was read
        throw file_error(path_, "truncated: expected " + std::to_string(las_.points) + " points, read " + std::to_string(i));
      const std::string_view r = data_.view();
      const glm::dvec3 integer(get<std::int32_t>(r, 0), get<std::int32_t>(r, 4), get<std::int32_t>(r, 8));
      part.world.push_back(integer * las_.scale + las_.offset);
      if (!is_finite(vec3(part.world.back())))
        throw file_error(path_, "point " + std::to_string(i) + " lies beyond float's range");
      part.scalars[0].values.push_back(get<std::uint16_t>(r, 12));
      part.scalars[1].values.push_back(las_.format <= 5 ? get<std::uint8_t>(r, 15) & 0x1F : get<std::uint8_t>(r, 16));
      if (las_.record.rgb != 0 && brightest_ > 0) {  // RGB fields all zero: a scanner that recorded none
        Rgb8 color;
        for (int c = 0; c < 3; ++c) {
          const auto channel = get<std::uint16_t>(r, las_.record.rgb + 2 * std::uint64_t(c));
          color[c] = brightest_ <= 255 ? std::uint8_t(channel) : io::channel_from_16bit(channel);
        }
        part.colors.push_back(color);
      }
      data_.consume(las_.record_length);
    }
    next_ = end;
    return std::size_t(end - begin);
  }

 private:
  std::filesystem::path path_;
  io::FileWindow data_;
  LasLayout las_;
  std::uint16_t brightest_ = 0;
  std::uint64_t next_ = 0;
};

}  // namespace

std::unique_ptr<PointStream> open_las_stream(const std::filesystem::path& path) {
  return std::make_unique<LasStream>(path);
}

PointCloud read_las(const std::filesystem::path& path) { return read_all(*open_las_stream(path)); }

}  // namespace pss
