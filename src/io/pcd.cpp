#include "pss/io/pcd.hpp"

#include <array>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "bytes.hpp"
#include "lzf.hpp"
#include "pss/core/error.hpp"
#include "pss/io/output_file.hpp"
#include "pss/io/point_cloud_file.hpp"
#include "text.hpp"

namespace pss {
namespace {

namespace fs = std::filesystem;
using io::load;

constexpr bool kSwap = std::endian::native != std::endian::little;
// Far beyond any PCL point type (the largest descriptors have a few hundred values), and
// small enough that a point's size cannot overflow.
constexpr std::uint64_t kMaxFields = 1 << 16, kMaxCount = 1 << 20;
// The most bytes LZF makes of one byte of input: a 3-byte back-reference copies 264.
constexpr std::uint64_t kMaxLzfRatio = 88;

struct Field {
  std::string_view name;
  char type = 'F';                // F float, I signed, U unsigned
  std::uint64_t size = 4;         // bytes of one value
  std::uint64_t count = 1;        // values per point
  std::uint64_t offset = 0;       // bytes before it in a binary point
  std::uint64_t first_value = 0;  // values before it on an ascii line
};

enum class Data { ascii, binary, binary_compressed };

struct Header {
  std::vector<Field> fields;
  std::uint64_t points = 0;
  std::uint64_t point_bytes = 0, point_values = 0;
  Data data = Data::ascii;
  std::size_t data_begin = 0;
  std::uint64_t lines = 0;  // so that ascii errors can name file lines
};

std::optional<std::uint64_t> parse_unsigned(std::string_view token) {
  std::uint64_t v = 0;
  const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), v);
  if (ec != std::errc() || end != token.data() + token.size()) return std::nullopt;
  return v;
}

// SIZE TYPE COUNT checked and laid out: offsets, and the point's size in bytes and values.
void lay_out(const fs::path& path, Header& h, std::span<const std::string_view> sizes,
             std::span<const std::string_view> types, std::span<const std::string_view> counts) {
  const std::size_t n = h.fields.size();
  if (n == 0) throw file_error(path, "header has no FIELDS");
  if (n > kMaxFields) throw file_error(path, "more than " + std::to_string(kMaxFields) + " FIELDS");
  const auto same_length = [&](std::span<const std::string_view> values, const char* key) {
    if (values.size() != n)
      throw file_error(path, std::string(key) + " has " + std::to_string(values.size()) + " values for " +
                                 std::to_string(n) + " FIELDS");
  };
  same_length(sizes, "SIZE");
  same_length(types, "TYPE");
  if (!counts.empty()) same_length(counts, "COUNT");  // COUNT may be left out: 1 each
  for (std::size_t i = 0; i < n; ++i) {
    Field& f = h.fields[i];
    const std::optional<std::uint64_t> size = parse_unsigned(sizes[i]);
    f.type = types[i].size() == 1 ? types[i][0] : '?';
    const bool valid = size && (f.type == 'F' ? (*size == 4 || *size == 8)
                                              : (f.type == 'I' || f.type == 'U') &&
                                                    (*size == 1 || *size == 2 || *size == 4 || *size == 8));
    if (!valid)
      throw file_error(path, "field " + quote(f.name) + " has an unknown TYPE " + quote(types[i]) + " with SIZE " +
                                 quote(sizes[i]));
    f.size = *size;
    if (!counts.empty()) {
      const std::optional<std::uint64_t> count = parse_unsigned(counts[i]);
      if (!count || *count == 0 || *count > kMaxCount)
        throw file_error(path, "field " + quote(f.name) + " has an invalid COUNT " + quote(counts[i]));
      f.count = *count;
    }
    f.offset = h.point_bytes;
    f.first_value = h.point_values;
    h.point_bytes += f.size * f.count;
    h.point_values += f.count;
  }
}

Header parse_header(const fs::path& path, std::string_view file) {
  Header h;
  io::Lines lines(file);
  std::vector<std::string_view> sizes, types, counts;
  std::optional<std::uint64_t> width, height, points;
  std::string_view line;
  bool data = false;
  while (!data && lines.next(line)) {
    const auto fail = [&](const std::string& problem) {
      return file_error(path, "line " + std::to_string(lines.number()) + ": " + problem);
    };
    const std::vector<std::string_view> words = io::split_words(line);
    if (words.empty() || words[0].starts_with('#')) continue;
    const std::string_view key = words[0];
    const std::vector<std::string_view> values(words.begin() + 1, words.end());
    const auto number = [&] {
      const std::optional<std::uint64_t> v = values.size() == 1 ? parse_unsigned(values[0]) : std::nullopt;
      if (!v) throw fail("malformed " + std::string(key) + " line " + quote(line));
      return *v;
    };
    if (key == "VERSION" || key == "VIEWPOINT") continue;
    if (key == "FIELDS") {
      for (std::string_view name : values) h.fields.push_back({name});
    } else if (key == "SIZE") sizes = values;
    else if (key == "TYPE") types = values;
    else if (key == "COUNT") counts = values;
    else if (key == "WIDTH") width = number();
    else if (key == "HEIGHT") height = number();
    else if (key == "POINTS") points = number();
    else if (key == "DATA") {
      if (values.size() == 1 && values[0] == "ascii") h.data = Data::ascii;
      else if (values.size() == 1 && values[0] == "binary") h.data = Data::binary;
      else if (values.size() == 1 && values[0] == "binary_compressed") h.data = Data::binary_compressed;
      else throw fail("unknown DATA " + quote(line));
      data = true;
    } else {
      throw fail("unexpected header line " + quote(line));
    }
  }
  if (!data) throw file_error(path, "not a PCD file (no DATA line)");
  h.data_begin = lines.end();
  h.lines = lines.number();
  lay_out(path, h, sizes, types, counts);

  if (width && height) {
    if (*height != 0 && *width > std::numeric_limits<std::uint64_t>::max() / *height)
      throw file_error(path, "WIDTH x HEIGHT overflows");
    if (points && *points != *width * *height)
      throw file_error(path, "WIDTH x HEIGHT = " + std::to_string(*width) + " x " + std::to_string(*height) +
                                 " is not POINTS " + std::to_string(*points));
    h.points = *width * *height;
  } else if (points) {
    h.points = *points;
  } else {
    throw file_error(path, "header has neither POINTS nor WIDTH and HEIGHT");
  }
  if (h.points == 0) throw file_error(path, "no points");
  return h;
}

// The fields pss takes, as indices into Header::fields: x y z, normal_x normal_y normal_z,
// then rgb or rgba.
constexpr std::size_t kX = 0, kNormal = 3, kColor = 6;
using Wanted = std::array<std::optional<std::size_t>, 7>;

Wanted wanted_fields(const fs::path& path, const Header& h) {
  const auto find = [&](std::string_view name) -> std::optional<std::size_t> {
    for (std::size_t i = 0; i < h.fields.size(); ++i)
      if (h.fields[i].name == name) return i;
    return std::nullopt;
  };
  Wanted w;
  constexpr std::string_view kNames[] = {"x", "y", "z", "normal_x", "normal_y", "normal_z"};
  for (std::size_t k = 0; k < 6; ++k) {
    w[k] = find(kNames[k]);
    if (w[k] && h.fields[*w[k]].count != 1)
      throw file_error(path, "field " + quote(kNames[k]) + " has COUNT " + std::to_string(h.fields[*w[k]].count) +
                                 ", not 1");
  }
  for (std::size_t k = kX; k < kNormal; ++k)
    if (!w[k]) throw file_error(path, "no field " + quote(kNames[k]));
  if (!(w[3] && w[4] && w[5])) w[3] = w[4] = w[5] = std::nullopt;
  w[kColor] = find("rgb");
  if (!w[kColor]) w[kColor] = find("rgba");
  if (w[kColor] && (h.fields[*w[kColor]].size != 4 || h.fields[*w[kColor]].count != 1)) w[kColor] = std::nullopt;
  return w;
}

// What one point gives: x y z and the normal as numbers, the colour as its packed bits.
struct PointValues {
  std::array<double, 6> v{};
  std::uint32_t rgb = 0;
};

// Collects the points, dropping those with a NaN coordinate with their normals and colours.
class CloudBuilder {
 public:
  CloudBuilder(const fs::path& path, const Wanted& wanted, std::uint64_t capacity)
      : path_(path), normals_(wanted[kNormal].has_value()), colors_(wanted[kColor].has_value()) {
    world_.reserve(capacity);
    if (normals_) cloud_.normals.reserve(capacity);
    if (colors_) cloud_.colors.reserve(capacity);
  }

  void add(std::uint64_t index, const PointValues& p) {
    if (std::isnan(p.v[0]) || std::isnan(p.v[1]) || std::isnan(p.v[2])) return;
    // Infinite, or a double beyond float's range: not PCL's invalid point, a broken one.
    world_.emplace_back(p.v[0], p.v[1], p.v[2]);
    if (!is_finite(vec3(world_.back())))
      throw file_error(path_, "point " + std::to_string(index) + " has an infinite coordinate");
    if (normals_) cloud_.normals.emplace_back(glm::dvec3(p.v[3], p.v[4], p.v[5]));
    if (colors_) cloud_.colors.emplace_back(p.rgb >> 16 & 255, p.rgb >> 8 & 255, p.rgb & 255);
  }

  PointCloud take(std::uint64_t points) {
    if (world_.empty())
      throw file_error(path_, "no points: all " + std::to_string(points) + " have a NaN coordinate");
    set_world_positions(cloud_, world_);
    tidy_normals(cloud_);
    return std::move(cloud_);
  }

 private:
  const fs::path& path_;
  bool normals_, colors_;
  std::vector<glm::dvec3> world_;
  PointCloud cloud_;
};

// PCL writes a packed rgb as the integer of its bits (newer versions, even for TYPE F) or as
// the float those bits make (older ones).
std::optional<std::uint32_t> packed_color(std::string_view token, const Field& field) {
  std::int64_t bits = 0;
  const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), bits);
  if (ec == std::errc() && end == token.data() + token.size() && bits >= std::numeric_limits<std::int32_t>::min() &&
      bits <= std::numeric_limits<std::uint32_t>::max())
    return static_cast<std::uint32_t>(bits);
  double value = 0;
  if (field.type == 'F' && io::parse_number(token, value)) return std::bit_cast<std::uint32_t>(float(value));
  return std::nullopt;
}

PointCloud read_ascii(const fs::path& path, const Header& h, const Wanted& wanted, std::string_view data) {
  // The shortest a point's line can be: one character and a separator per value.
  CloudBuilder cloud(path, wanted, std::min(h.points, data.size() / (2 * h.point_values) + 1));
  io::Lines lines(data);
  std::uint64_t read = 0;
  std::string_view line;
  while (lines.next(line)) {
    const auto fail = [&](const std::string& problem) {
      return file_error(path, "line " + std::to_string(h.lines + lines.number()) + ": " + problem);
    };
    const std::vector<std::string_view> words = io::split_words(line);
    if (words.empty()) continue;
    if (read == h.points) throw fail("more points than the header's " + std::to_string(h.points));
    if (words.size() != h.point_values)
      throw fail("expected " + std::to_string(h.point_values) + " values, found " + std::to_string(words.size()));
    PointValues p;
    for (std::size_t k = 0; k < kColor; ++k) {
      if (!wanted[k]) continue;
      const std::string_view token = words[h.fields[*wanted[k]].first_value];
      if (!io::parse_number(token, p.v[k])) throw fail("malformed number " + quote(token));
    }
    if (wanted[kColor]) {
      const Field& field = h.fields[*wanted[kColor]];
      const std::optional<std::uint32_t> rgb = packed_color(words[field.first_value], field);
      if (!rgb) throw fail("malformed colour " + quote(words[field.first_value]));
      p.rgb = *rgb;
    }
    cloud.add(read++, p);
  }
  if (read < h.points)
    throw file_error(path, "truncated: expected " + std::to_string(h.points) + " points, read " + std::to_string(read));
  return cloud.take(h.points);
}

double value_at(const char* p, const Field& f) {
  switch (f.size) {
    case 1: return f.type == 'I' ? double(load<std::int8_t>(p, kSwap)) : double(load<std::uint8_t>(p, kSwap));
    case 2: return f.type == 'I' ? double(load<std::int16_t>(p, kSwap)) : double(load<std::uint16_t>(p, kSwap));
    case 4:
      if (f.type == 'F') return load<float>(p, kSwap);
      return f.type == 'I' ? double(load<std::int32_t>(p, kSwap)) : double(load<std::uint32_t>(p, kSwap));
    default:
      if (f.type == 'F') return load<double>(p, kSwap);
      return f.type == 'I' ? double(load<std::int64_t>(p, kSwap)) : double(load<std::uint64_t>(p, kSwap));
  }
}

// `data` holds all the points: one after the other (binary), or, decompressed, each field's
// values for all points one after the other (binary_compressed).
PointCloud read_binary(const fs::path& path, const Header& h, const Wanted& wanted, std::string_view data,
                       bool fields_apart) {
  CloudBuilder cloud(path, wanted, h.points);
  std::array<std::uint64_t, 7> base{}, stride{};
  for (std::size_t k = 0; k < wanted.size(); ++k) {
    if (!wanted[k]) continue;
    const Field& f = h.fields[*wanted[k]];
    base[k] = fields_apart ? f.offset * h.points : f.offset;
    stride[k] = fields_apart ? f.size * f.count : h.point_bytes;
  }
  for (std::uint64_t i = 0; i < h.points; ++i) {
    PointValues p;
    for (std::size_t k = 0; k < kColor; ++k)
      if (wanted[k]) p.v[k] = value_at(data.data() + base[k] + i * stride[k], h.fields[*wanted[k]]);
    if (wanted[kColor]) p.rgb = load<std::uint32_t>(data.data() + base[kColor] + i * stride[kColor], kSwap);
    cloud.add(i, p);
  }
  return cloud.take(h.points);
}

}  // namespace

PointCloud read_pcd(const fs::path& path) {
  const std::string file = read_file(path);
  const Header h = parse_header(path, file);
  const Wanted wanted = wanted_fields(path, h);
  const std::string_view data = std::string_view(file).substr(h.data_begin);
  const std::string points = std::to_string(h.points) + " points of " + std::to_string(h.point_bytes) + " bytes";
  switch (h.data) {
    case Data::ascii: return read_ascii(path, h, wanted, data);
    case Data::binary:
      if (h.points > data.size() / h.point_bytes)
        throw file_error(path, "truncated: " + points + " need more than the " + std::to_string(data.size()) +
                                   " bytes after the header");
      return read_binary(path, h, wanted, data, false);
    case Data::binary_compressed: {
      if (data.size() < 8) throw file_error(path, "truncated: no compressed sizes after the header");
      const std::uint64_t compressed = load<std::uint32_t>(data.data(), kSwap);
      const std::uint64_t uncompressed = load<std::uint32_t>(data.data() + 4, kSwap);
      if (compressed > data.size() - 8)
        throw file_error(path, "truncated: " + std::to_string(compressed) + " compressed bytes declared, " +
                                   std::to_string(data.size() - 8) + " present");
      if (h.points > uncompressed / h.point_bytes || h.points * h.point_bytes != uncompressed)
        throw file_error(path, "the uncompressed size " + std::to_string(uncompressed) + " is not that of " + points);
      // Checked before allocating: a lying size cannot claim more than LZF can make.
      if (uncompressed > kMaxLzfRatio * compressed)
        throw file_error(path, std::to_string(compressed) + " compressed bytes cannot make " +
                                   std::to_string(uncompressed) + " (LZF expands at most 88 times)");
      std::string buffer(uncompressed, '\0');
      const std::string_view problem = io::lzf_decompress(data.substr(8, compressed), buffer);
      if (!problem.empty()) throw file_error(path, "corrupt compressed data: " + std::string(problem));
      return read_binary(path, h, wanted, buffer, true);
    }
  }
  return {};
}

}  // namespace pss
