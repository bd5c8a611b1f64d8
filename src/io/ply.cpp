#include "pss/io/ply.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstring>
#include <limits>
#include <memory>
#include <optional>
#include <string_view>
#include <type_traits>
#include <vector>

#include "pss/core/error.hpp"
#include "pss/io/point_cloud_file.hpp"
#include "pss/io/point_stream.hpp"
#include "bytes.hpp"
#include "color.hpp"
#include "file_window.hpp"
#include "point_streams.hpp"
#include "ply_types.hpp"
#include "text.hpp"

namespace pss {
namespace {

namespace fs = std::filesystem;

using namespace io;  // the PLY scalar types (ply_types.hpp)

struct Property {
  std::string name;
  Scalar type;                  // the value's type, or a list's item type
  std::optional<Scalar> count;  // set for lists: the type of the item count
};

struct Element {
  std::string name;
  std::uint64_t count = 0;
  std::vector<Property> properties;
};

enum class Format { Ascii, BinaryLittleEndian, BinaryBigEndian };

struct Header {
  Format format = Format::Ascii;
  std::vector<Element> elements;
  std::size_t data_begin = 0;  // first byte after the end_header line
  int lines = 0;               // so that ascii errors can name file lines
};

Header parse_header(const fs::path& path, std::string_view file) {
  if (!file.starts_with("ply\n") && !file.starts_with("ply\r\n"))
    throw file_error(path, "not a PLY file (missing 'ply' magic)");
  Header header;
  bool has_format = false;
  std::size_t pos = 0;
  int line_number = 0;
  const auto fail = [&](const std::string& problem) {
    return file_error(path, "line " + std::to_string(line_number) + ": " + problem);
  };
  const auto scalar = [&](std::string_view name) {
    const std::optional<Scalar> type = scalar_named(name);
    if (!type) throw fail("unknown property type " + quote(name));
    return *type;
  };
  // Every header line, end_header's included, ends with '\n' (CRLF tolerated).
  for (std::size_t end; (end = file.find('\n', pos)) != std::string_view::npos;) {
    std::string_view line = file.substr(pos, end - pos);
    if (line.ends_with('\r')) line.remove_suffix(1);
    pos = end + 1;
    if (++line_number == 1) continue;  // the magic
    const std::vector<std::string_view> words = io::split_words(line);
    if (words.empty() || words[0] == "comment" || words[0] == "obj_info") continue;
    if (words[0] == "format" && words.size() >= 2) {
      if (words[1] == "ascii") header.format = Format::Ascii;
      else if (words[1] == "binary_little_endian") header.format = Format::BinaryLittleEndian;
      else if (words[1] == "binary_big_endian") header.format = Format::BinaryBigEndian;
      else throw file_error(path, "unknown format " + quote(words[1]));
      has_format = true;
    } else if (words[0] == "element" && words.size() == 3) {
      Element element{std::string(words[1]), 0, {}};
      const auto [end_of_count, ec] =
          std::from_chars(words[2].data(), words[2].data() + words[2].size(), element.count);
      if (ec != std::errc() || end_of_count != words[2].data() + words[2].size())
        throw fail("malformed element count " + quote(words[2]));
      header.elements.push_back(std::move(element));
    } else if (words[0] == "property" && (words.size() == 3 || words.size() == 5)) {
      if (header.elements.empty()) throw fail("property before any element");
      Property property;
      if (words.size() == 5 && words[1] == "list")
        property = {std::string(words[4]), scalar(words[3]), scalar(words[2])};
      else if (words.size() == 3)
        property = {std::string(words[2]), scalar(words[1]), std::nullopt};
      else
        throw fail("malformed property line " + quote(line));
      header.elements.back().properties.push_back(std::move(property));
    } else if (words[0] == "end_header") {
      if (!has_format) throw file_error(path, "header has no 'format' line");
      header.data_begin = pos;
      header.lines = line_number;
      return header;
    } else {
      throw fail("unexpected header line " + quote(line));
    }
  }
  throw file_error(path, "header has no 'end_header' line");
}

// Thrown by the cursors when the data ends early; the record loop, which knows what was
// expected, turns it into the message.
struct EndOfData {};

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }

// Whitespace-separated tokens; records usually sit one per line, but PLY does not require it.
class AsciiCursor {
 public:
  AsciiCursor(const fs::path& path, io::FileWindow& data, int first_line) : path_(path), data_(data), line_(first_line) {}

  std::uint64_t remaining() const { return data_.remaining(); }
  // The shortest a value can be: one character and a separator.
  static std::size_t min_bytes(Scalar) { return 2; }

  double value(Scalar) {
    std::string_view token = next();
    if (token.size() > 1 && token[0] == '+') token.remove_prefix(1);  // from_chars rejects '+'
    double v = 0;
    const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), v);
    if (ec == std::errc::result_out_of_range) fail("number out of range " + quote(token));
    if (ec != std::errc() || end != token.data() + token.size())
      fail("malformed number " + quote(token));
    return v;
  }
  void skip(Scalar, std::uint64_t n = 1) {
    for (std::uint64_t i = 0; i < n; ++i) next();
  }
  // After a vertex's `properties` values, the rest of its line must be blank: a line of one
  // value more would otherwise shift every later vertex by a value, silently (a new user's
  // trial). A vertex may still span lines.
  void end_record(std::size_t properties) {
    for (;;) {
      const std::string_view v = data_.view();
      std::size_t i = 0;
      while (i < v.size() && (v[i] == ' ' || v[i] == '\t' || v[i] == '\r')) ++i;
      data_.consume(i);
      if (i < v.size()) {
        if (v[i] == '\n') return;
        fail("values left on the line after a vertex's " + std::to_string(properties) +
             " properties (one vertex a line, as the header declares them)");
      }
      if (!data_.fill(1)) return;  // the file ends with the record
    }
  }
  [[noreturn]] void fail(const std::string& problem) const {
    throw file_error(path_, "line " + std::to_string(line_) + ": " + problem);
  }

 private:
  // The next token, valid until the next call.
  std::string_view next() {
    for (;;) {
      const std::string_view v = data_.view();
      std::size_t i = 0;
      while (i < v.size() && is_space(v[i])) line_ += v[i++] == '\n';
      data_.consume(i);
      if (i < v.size()) break;
      if (!data_.fill(1)) throw EndOfData{};
    }
    for (;;) {
      const std::string_view v = data_.view();
      std::size_t j = 0;
      while (j < v.size() && !is_space(v[j])) ++j;
      if (j < v.size() || !data_.fill(v.size() + 1)) {
        data_.consume(j);
        return v.substr(0, j);
      }
      if (v.size() >= kLongestToken) fail("a value longer than " + std::to_string(kLongestToken) + " characters");
    }
  }

  static constexpr std::size_t kLongestToken = 4096;
  const fs::path& path_;
  io::FileWindow& data_;
  int line_;
};

class BinaryCursor {
 public:
  BinaryCursor(const fs::path& path, io::FileWindow& data, std::endian endian)
      : path_(path), data_(data), data_begin_(data.offset()), swap_(endian != std::endian::native) {}

  std::uint64_t remaining() const { return data_.remaining(); }
  static std::size_t min_bytes(Scalar type) { return size_of(type); }

  double value(Scalar type) {
    const char* p = take(size_of(type));
    switch (type) {
      case Scalar::int8: return load<std::int8_t>(p, swap_);
      case Scalar::uint8: return load<std::uint8_t>(p, swap_);
      case Scalar::int16: return load<std::int16_t>(p, swap_);
      case Scalar::uint16: return load<std::uint16_t>(p, swap_);
      case Scalar::int32: return load<std::int32_t>(p, swap_);
      case Scalar::uint32: return load<std::uint32_t>(p, swap_);
      case Scalar::float32: return load<float>(p, swap_);
      case Scalar::float64: return load<double>(p, swap_);
    }
    return 0;
  }
  void skip(Scalar type, std::uint64_t n = 1) {
    if (!data_.skip(n * size_of(type))) throw EndOfData{};
  }
  void end_record(std::size_t) {}  // records have their sizes
  [[noreturn]] void fail(const std::string& problem) const {
    throw file_error(path_, "byte " + std::to_string(data_.offset() - data_begin_) + " of the data: " + problem);
  }

 private:
  // The next `bytes` bytes (at most 8), valid until the next call.
  const char* take(std::size_t bytes) {
    if (!data_.fill(bytes)) throw EndOfData{};
    const char* p = data_.view().data();
    data_.consume(bytes);
    return p;
  }

  const fs::path& path_;
  io::FileWindow& data_;
  std::uint64_t data_begin_;
  bool swap_;
};

// Lists are never needed (faces, or per-vertex lists): only their length is read.
template <class Cursor>
void skip_list(Cursor& in, const Property& list) {
  const double n = in.value(*list.count);
  if (!whole_in_range<std::uint32_t>(n)) in.fail("malformed list count " + text_of(n));
  in.skip(list.type, static_cast<std::uint64_t>(n));
}

std::string describe(const Element& element) {
  const std::string n = std::to_string(element.count);
  return element.name == "vertex" ? n + " vertices" : n + " " + quote(element.name) + " elements";
}

// Runs read_record for records [begin, end) of the element, reporting truncation as
// "expected N, read M".
template <class ReadRecord>
void for_each_record(const fs::path& path, const Element& element, std::uint64_t begin, std::uint64_t end,
                     ReadRecord read_record) {
  if (element.properties.empty()) return;  // no bytes to read, however large the count
  std::uint64_t i = begin;
  try {
    for (; i < end; ++i) read_record(i);
  } catch (const EndOfData&) {
    throw file_error(path,
                     "truncated: expected " + describe(element) + ", read " + std::to_string(i));
  }
}

// The vertex properties read, by slot: x y z, nx ny nz, red green blue (or MeshLab's older
// diffuse_red ...), then the other scalars kept (PointCloud::scalars) from slot kSlots on.
constexpr std::string_view kVertexNames[] = {"x", "y", "z", "nx", "ny", "nz", "red", "green", "blue"};
constexpr int kNormal = 3, kColor = 6, kSlots = 9;
// The most other scalars kept; later ones are skipped like lists. Real files carry a few (the
// bunny's confidence and intensity, a label), and a header naming thousands of properties
// should not make every output record carry them.
constexpr std::size_t kMaxScalars = 64;

// Also PCL's normal_x normal_y normal_z, and MeshLab's older diffuse_red ...
bool names_slot(std::string_view name, int k) {
  if (name == kVertexNames[k]) return true;
  if (k >= kColor) return name.starts_with("diffuse_") && name.substr(8) == kVertexNames[k];
  return k >= kNormal && name.starts_with("normal_") && name.size() == 8 && name[7] == "xyz"[k - kNormal];
}

// Which slot each vertex property fills (-1: skipped). Normals and colours count only when
// all three of their properties are present. A scalar is kept when no slot has its name
// (a second 'x', or an 'nx' without 'nz', is skipped) and no earlier kept scalar has it, so
// that an output never names a property twice.
std::vector<int> vertex_slots(const fs::path& path, const Element& vertex) {
  std::vector<int> slots(vertex.properties.size(), -1);
  std::array<bool, kSlots> found{};
  std::vector<std::string_view> kept;
  for (std::size_t i = 0; i < slots.size(); ++i) {
    const Property& p = vertex.properties[i];
    if (p.count) continue;
    bool named = false;
    for (int k = 0; k < kSlots; ++k) {
      if (!names_slot(p.name, k)) continue;
      named = true;
      if (!found[k]) slots[i] = k, found[k] = true;
    }
    if (!named && kept.size() < kMaxScalars && std::find(kept.begin(), kept.end(), p.name) == kept.end()) {
      slots[i] = kSlots + int(kept.size());
      kept.push_back(p.name);
    }
  }
  for (int k = 0; k < kNormal; ++k)
    if (!found[k])
      throw file_error(path, "vertex element has no '" + std::string(kVertexNames[k]) + "' property");
  for (const int group : {kNormal, kColor})
    if (!(found[group] && found[group + 1] && found[group + 2]))
      for (int& s : slots) s = s >= group && s < group + 3 ? -1 : s;
  return slots;
}

// A colour channel of any type: floats from 0..1, 16-bit integers scaled from 0..65535, the
// others as 0..255 values (clamped).
std::uint8_t color_channel(double v, Scalar type) {
  switch (type) {
    case Scalar::float32:
    case Scalar::float64: return io::channel_from_unit(v);
    case Scalar::int16:
    case Scalar::uint16: return io::channel_from_16bit(v > 0 ? std::uint32_t(v) : 0);
    default: return static_cast<std::uint8_t>(std::clamp(v, 0.0, 255.0));
  }
}

// A kept scalar's value, refused when it does not fit its type (ASCII "3.5" for an int).
template <class Cursor>
double scalar_value(Cursor& in, const Property& p) {
  const double v = in.value(p.type);
  const std::optional<double> kept = as_type(v, p.type);
  if (!kept)
    in.fail("value " + text_of(v) + " of " + quote(p.name) + " does not fit its type " + std::string(name_of(p.type)));
  return *kept;
}

// The most records of an element the remaining bytes could hold. Reserving no more than
// that keeps a corrupt count from allocating gigabytes before the truncation shows.
template <class Cursor>
std::uint64_t max_records(const Cursor& in, const Element& element) {
  std::uint64_t min_record = 0;
  for (const Property& p : element.properties) min_record += in.min_bytes(p.count.value_or(p.type));
  return min_record == 0 ? 0 : (in.remaining() + 1) / min_record;
}

// Reads on until the window holds the header's last line, or the file or kLongestHeader ends
// (parse_header then says what is wrong).
constexpr std::size_t kLongestHeader = std::size_t(1) << 24;
Header read_header(const fs::path& path, io::FileWindow& file) {
  for (std::size_t want = 1 << 16;; want *= 2) {
    file.fill(std::min<std::uint64_t>(std::min(want, kLongestHeader), file.remaining()));
    const std::string_view v = file.view();
    const std::size_t end = v.find("\nend_header");
    if ((end != std::string_view::npos && v.find('\n', end + 1) != std::string_view::npos) ||
        v.size() >= file.remaining() || want >= kLongestHeader)
      return parse_header(path, v);
  }
}

// The vertices of a PLY file, a part at a time, through a cursor of its format.
template <class Cursor>
class PlyStream final : public PointStream {
 public:
  PlyStream(const fs::path& path, std::unique_ptr<io::FileWindow> file, Header header, int first_line)
      : path_(path), file_(std::move(file)), header_(std::move(header)), in_(make_cursor(first_line)) {
    const auto vertex = std::find_if(header_.elements.begin(), header_.elements.end(),
                                     [](const Element& e) { return e.name == "vertex"; });
    if (vertex == header_.elements.end()) throw file_error(path, "no vertex element");
    vertex_ = &*vertex;
    slots_ = vertex_slots(path, *vertex_);
    if (vertex_->count == 0) throw file_error(path, "no vertices");
    for (auto e = header_.elements.begin(); e != vertex; ++e) {
      for_each_record(path, *e, 0, e->count, [&](std::uint64_t) {
        for (const Property& p : e->properties) {
          if (p.count) skip_list(in_, p);
          else in_.skip(p.type);
        }
      });
    }
    normals_ = std::find(slots_.begin(), slots_.end(), kNormal) != slots_.end();
    colors_ = std::find(slots_.begin(), slots_.end(), kColor) != slots_.end();
    for (std::size_t j = 0; j < slots_.size(); ++j)
      if (slots_[j] >= kColor && slots_[j] < kSlots) color_types_[slots_[j] - kColor] = vertex_->properties[j].type;
    mesh_vertices_ = std::any_of(header_.elements.begin(), header_.elements.end(),
                                 [](const Element& e) { return e.name == "face" && e.count > 0; });
    // Positions of floats or of integers of two bytes at most are kept in floats, which hold
    // them exactly: half the memory of doubles (issue 28).
    for (std::size_t j = 0; j < slots_.size(); ++j) {
      const Scalar type = vertex_->properties[j].type;
      if (slots_[j] >= 0 && slots_[j] < 3)
        float_positions_ = float_positions_ && (type == Scalar::float32 || size_of(type) <= 2);
    }
    expected_ = std::min(vertex_->count, max_records(in_, *vertex_));
  }

  std::uint64_t declared_count() const override { return expected_; }
  bool float_positions() const override { return float_positions_; }
  bool mesh_vertices() const override { return mesh_vertices_; }

  std::size_t read(PointPart& part, std::size_t most) override {
    if (part.scalars.empty())
      for (std::size_t j = 0; j < slots_.size(); ++j)
        if (slots_[j] >= kSlots) part.scalars.push_back({vertex_->properties[j].name, vertex_->properties[j].type, {}});
    const std::uint64_t end = std::min<std::uint64_t>(vertex_->count, next_ + most);
    const std::uint64_t begin = next_;
    // Elements after the vertices are not read: nothing there is needed.
    for_each_record(path_, *vertex_, begin, end, [&](std::uint64_t i) { read_vertex(part, i); });
    next_ = end;
    return std::size_t(end - begin);
  }

 private:
  Cursor make_cursor(int first_line) {
    if constexpr (std::is_same_v<Cursor, AsciiCursor>) return AsciiCursor(path_, *file_, first_line);
    else return BinaryCursor(path_, *file_, header_.format == Format::BinaryBigEndian ? std::endian::big : std::endian::little);
  }

  void read_vertex(PointPart& part, std::uint64_t i) {
    double v[kSlots] = {};
    for (std::size_t j = 0; j < slots_.size(); ++j) {
      const Property& p = vertex_->properties[j];
      if (p.count) skip_list(in_, p);
      else if (slots_[j] >= kSlots) part.scalars[std::size_t(slots_[j] - kSlots)].values.push_back(scalar_value(in_, p));
      else if (slots_[j] >= 0) v[slots_[j]] = in_.value(p.type);
      else in_.skip(p.type);
    }
    in_.end_record(slots_.size());
    // A double beyond float range becomes infinite here, and is refused with the NaNs.
    const vec3 p(glm::dvec3(v[0], v[1], v[2]));
    if (!is_finite(p)) throw file_error(path_, "vertex " + std::to_string(i) + " has a non-finite coordinate");
    part.world.emplace_back(v[0], v[1], v[2]);
    if (normals_) part.normals.push_back(vec3(glm::dvec3(v[3], v[4], v[5])));
    if (colors_) {
      if (!std::isfinite(v[6]) || !std::isfinite(v[7]) || !std::isfinite(v[8]))
        throw file_error(path_, "vertex " + std::to_string(i) + " has a non-finite colour");
      part.colors.emplace_back(color_channel(v[6], color_types_[0]), color_channel(v[7], color_types_[1]),
                               color_channel(v[8], color_types_[2]));
    }
  }

  fs::path path_;
  std::unique_ptr<io::FileWindow> file_;
  Header header_;
  Cursor in_;
  const Element* vertex_ = nullptr;
  std::vector<int> slots_;
  bool normals_ = false, colors_ = false, mesh_vertices_ = false, float_positions_ = true;
  std::array<Scalar, 3> color_types_{};
  std::uint64_t expected_ = 0, next_ = 0;
};

}  // namespace

std::unique_ptr<PointStream> open_ply_stream(const fs::path& path) {
  auto file = std::make_unique<io::FileWindow>(path);
  Header header = read_header(path, *file);
  file->consume(header.data_begin);
  const int first_line = header.lines + 1;
  if (header.format == Format::Ascii)
    return std::make_unique<PlyStream<AsciiCursor>>(path, std::move(file), std::move(header), first_line);
  return std::make_unique<PlyStream<BinaryCursor>>(path, std::move(file), std::move(header), first_line);
}

PointCloud read_ply(const fs::path& path) { return read_all(*open_ply_stream(path)); }

}  // namespace pss
