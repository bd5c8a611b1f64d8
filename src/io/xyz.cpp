#include "pss/io/xyz.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "pss/core/error.hpp"
#include "pss/core/memory.hpp"
#include "pss/io/point_cloud_file.hpp"
#include "pss/io/point_cloud_writer.hpp"
#include "file_window.hpp"
#include "point_encoders.hpp"
#include "point_streams.hpp"

namespace pss {
namespace {

bool is_separator(char c) { return c == ' ' || c == '\t' || c == ',' || c == '\r'; }

// Six numbers of a double's 17 digits with their separators fit many times over; a longer
// line is no point's, and is not held whole.
constexpr std::size_t kLongestLine = std::size_t(1) << 20;

// The next line without its '\n' (the last may have none), valid until the next call; false
// at the end of the file. A line beyond kLongestLine comes back cut to one character more.
bool next_line(io::FileWindow& file, std::string_view& line) {
  for (std::size_t want = 1;; want = file.view().size() + 1) {
    if (!file.fill(want) && file.view().empty()) return false;
    const std::string_view v = file.view();
    const std::size_t end = v.find('\n');
    if (end != std::string_view::npos) {
      line = v.substr(0, end);
      file.consume(end + 1);
      return true;
    }
    if (v.size() > kLongestLine || v.size() < want) {  // too long, or the file's last line
      line = v.substr(0, std::min(v.size(), kLongestLine + 1));
      file.consume(v.size());
      return true;
    }
  }
}

bool is_channel(double v) { return v >= 0 && v <= 255 && v == std::floor(v); }

// Whether a column triple holds colours over the rows: integers from 0 to 255, some above 1
// (no unit normal's), not all of one length (a normal scaled by a constant, "0 0 5", is).
template <class Rows>
bool holds_colours(const Rows& rows, int first) {
  bool above_one = false, one_length = true;
  double length = -1;
  for (const auto& row : rows) {
    const double* v = row.v + first;
    if (!is_channel(v[0]) || !is_channel(v[1]) || !is_channel(v[2])) return false;
    above_one = above_one || std::max({v[0], v[1], v[2]}) > 1;
    const double l = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    if (length < 0) length = l;
    one_length = one_length && std::abs(l - length) <= 1e-3 * length;
  }
  return above_one && !one_length;
}

// What the columns after x y z hold: nothing, nx ny nz, r g b, or both in either order;
// decided by the first kDecidingRows rows (holds_colours), then fixed.
enum class Extra { undecided, none, normals, colours, colours_normals, normals_colours };

// The points of an XYZ file, a line at a time.
class XyzStream final : public PointStream {
 public:
  explicit XyzStream(const std::filesystem::path& path) : path_(path), file_(path) {}

  std::uint64_t declared_count() const override { return 0; }

  std::size_t read(PointPart& part, std::size_t most) override {
    // What the columns hold is decided by the first rows, however many a caller asks for first.
    if (extra_ == Extra::undecided) {
      for (Row row; pending_.size() < kDecidingRows && next_row(row);) pending_.push_back(row);
      decide(pending_);
    }
    const int colour = extra_ == Extra::colours || extra_ == Extra::colours_normals ? 3
                       : extra_ == Extra::normals_colours                          ? 6
                                                                                   : 0;
    const int normal = extra_ == Extra::normals || extra_ == Extra::normals_colours ? 3
                       : extra_ == Extra::colours_normals                           ? 6
                                                                                    : 0;
    std::size_t added = 0;
    for (Row row; added < most; ++added) {
      if (next_pending_ < pending_.size())
        row = pending_[next_pending_++];
      else if (!next_row(row))
        break;
      const double* v = row.v;
      part.world.emplace_back(v[0], v[1], v[2]);
      if (colour > 0) {
        if (!is_channel(v[colour]) || !is_channel(v[colour + 1]) || !is_channel(v[colour + 2]))
          throw file_error(path_, "line " + std::to_string(row.line) + ": columns " + std::to_string(colour + 1) + "-" +
                                      std::to_string(colour + 3) +
                                      " are a colour (r g b) on the lines before, but here not integers from 0 to 255");
        part.colors.emplace_back(std::uint8_t(v[colour]), std::uint8_t(v[colour + 1]), std::uint8_t(v[colour + 2]));
      }
      if (normal > 0) part.normals.emplace_back(v[normal], v[normal + 1], v[normal + 2]);
    }
    if (next_pending_ == pending_.size()) release(pending_), next_pending_ = 0;
    points_ += added;
    if (added == 0 && points_ == 0) throw file_error(path_, "no points");
    return added;
  }

 private:
  static constexpr std::size_t kDecidingRows = 4096;
  struct Row {
    double v[9];  // read in double: a georeferenced cloud's digits (cloud.hpp)
    int line;
  };

  // The next point line's numbers; false at the end of the file.
  bool next_row(Row& row) {
    for (std::string_view line; next_line(file_, line);) {
      ++line_number_;
      const auto fail = [&](const std::string& problem) {
        return file_error(path_, "line " + std::to_string(line_number_) + ": " + problem);
      };
      if (line.size() > kLongestLine)
        throw fail("longer than " + std::to_string(kLongestLine) + " characters: not a file of points");
      double* v = row.v;
      row.line = line_number_;
      std::size_t count = 0;
      for (std::size_t i = 0; i < line.size();) {
        if (is_separator(line[i])) {
          ++i;
          continue;
        }
        if (count == 0 && line[i] == '#') break;  // a comment line
        std::size_t j = i;
        while (j < line.size() && !is_separator(line[j])) ++j;
        std::string_view token = line.substr(i, j - i);
        i = j;
        if (count == 9) throw fail("more than 9 numbers");
        if (token.size() > 1 && token[0] == '+') token.remove_prefix(1);  // from_chars rejects '+'
        const auto [stop, ec] = std::from_chars(token.data(), token.data() + token.size(), v[count]);
        if (ec == std::errc::result_out_of_range || (std::isinf(float(v[count])) && !std::isinf(v[count])))
          throw fail("number out of range " + quote(token, 40));
        if (ec != std::errc() || stop != token.data() + token.size())
          throw fail("malformed number " + quote(token, 40));
        ++count;
      }
      if (count == 0) continue;  // blank or comment
      if (columns_ == 0) {
        if (count != 3 && count != 6 && count != 9)
          throw fail("expected 3, 6 or 9 numbers (x y z [nx ny nz] [r g b]), found " + std::to_string(count));
        columns_ = count;
        first_point_line_ = line_number_;
      } else if (count != columns_) {
        throw fail("found " + std::to_string(count) + " numbers, but line " + std::to_string(first_point_line_) +
                   " has " + std::to_string(columns_));
      }
      if (!is_finite(vec3(glm::dvec3(v[0], v[1], v[2])))) throw fail("non-finite coordinate");
      return true;
    }
    return false;
  }

  void decide(const std::vector<Row>& rows) {
    if (columns_ <= 3) {
      extra_ = Extra::none;
    } else if (columns_ == 6) {
      extra_ = holds_colours(rows, 3) ? Extra::colours : Extra::normals;
    } else {
      const bool first = holds_colours(rows, 3), second = holds_colours(rows, 6);
      if (first == second)
        throw file_error(path_, "9 numbers a line, but " + std::string(first ? "both" : "neither") +
                                    " of columns 4-6 and 7-9 hold a colour (r g b, integers from 0 to 255) beside "
                                    "a normal (nx ny nz)");
      extra_ = first ? Extra::colours_normals : Extra::normals_colours;
    }
  }

 private:
  std::filesystem::path path_;
  io::FileWindow file_;
  std::size_t columns_ = 0;  // fixed by the first point line
  Extra extra_ = Extra::undecided;
  std::vector<Row> pending_;  // the rows read to decide, not yet given
  std::size_t next_pending_ = 0;
  int first_point_line_ = 0, line_number_ = 0;
  std::uint64_t points_ = 0;
};

// One point a line; XYZ has no header.
class XyzEncoder final : public PointsEncoder {
 public:
  explicit XyzEncoder(const PointsLayout& layout) : normals_(layout.normals), recentred_(layout.has_origin()) {}

  void write_header(std::ostream&) override {}

  void write(std::ostream& out, const PointCloud& part, std::span<const PlyIntProperty>) override {
    std::string lines;
    // Floats in %.9g, which reads back exactly; a cloud away from the world's origin
    // (cloud.hpp) in %.17g, its world positions being doubles.
    const int digits = recentred_ ? 17 : 9;
    char line[160];  // three %.17g and three %.9g numbers take at most 3 * 25 + 3 * 16 bytes
    for (std::size_t i = 0; i < part.size(); ++i) {
      const glm::dvec3 p = recentred_ ? part.world(i) : glm::dvec3(part.positions[i]);  // keeps −0
      int length = 0;
      if (normals_) {
        const vec3 n = part.normals[i];
        length = std::snprintf(line, sizeof line, "%.*g %.*g %.*g %.9g %.9g %.9g\n", digits, p.x, digits, p.y, digits,
                               p.z, n.x, n.y, n.z);
      } else {
        length = std::snprintf(line, sizeof line, "%.*g %.*g %.*g\n", digits, p.x, digits, p.y, digits, p.z);
      }
      lines.append(line, std::size_t(length));
      if (lines.size() > (1u << 20)) {  // one write a megabyte, without a copy of a large part
        out.write(lines.data(), std::streamsize(lines.size()));
        lines.clear();
      }
    }
    out.write(lines.data(), std::streamsize(lines.size()));
  }

 private:
  bool normals_, recentred_;
};

}  // namespace

std::unique_ptr<PointStream> open_xyz_stream(const std::filesystem::path& path) {
  return std::make_unique<XyzStream>(path);
}

PointCloud read_xyz(const std::filesystem::path& path) { return read_all(*open_xyz_stream(path)); }

std::unique_ptr<PointsEncoder> xyz_encoder(const PointsLayout& layout) { return std::make_unique<XyzEncoder>(layout); }

void write_xyz(const std::filesystem::path& path, const PointCloud& cloud) {
  // XYZ has no room for colours or scalars: the layout leaves them out, so the cloud's are not
  // looked at.
  PointsLayout layout = layout_of(cloud);
  layout.colors = false;
  layout.scalars.clear();
  PointCloudWriter writer(path, PointsFormat::xyz, std::move(layout));
  writer.append(cloud);
  writer.commit();
}

}  // namespace pss
