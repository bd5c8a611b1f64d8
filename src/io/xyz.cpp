#include "pss/io/xyz.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <string_view>
#include <utility>

#include "pss/core/error.hpp"
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

// The points of an XYZ file, a line at a time.
class XyzStream final : public PointStream {
 public:
  explicit XyzStream(const std::filesystem::path& path) : path_(path), file_(path) {}

  std::uint64_t declared_count() const override { return 0; }

  std::size_t read(PointPart& part, std::size_t most) override {
    std::size_t added = 0;
    for (std::string_view line; added < most && next_line(file_, line);) {
      ++line_number_;
      const auto fail = [&](const std::string& problem) {
        return file_error(path_, "line " + std::to_string(line_number_) + ": " + problem);
      };
      if (line.size() > kLongestLine)
        throw fail("longer than " + std::to_string(kLongestLine) + " characters: not a file of points");
      double v[6];  // read in double: a georeferenced cloud's digits (cloud.hpp)
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
        if (count == 6) throw fail("more than 6 numbers");
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
        if (count != 3 && count != 6)
          throw fail("expected 3 or 6 numbers (x y z [nx ny nz]), found " + std::to_string(count));
        columns_ = count;
        first_point_line_ = line_number_;
      } else if (count != columns_) {
        throw fail("found " + std::to_string(count) + " numbers, but line " + std::to_string(first_point_line_) +
                   " has " + std::to_string(columns_));
      }
      if (!is_finite(vec3(glm::dvec3(v[0], v[1], v[2])))) throw fail("non-finite coordinate");
      part.world.emplace_back(v[0], v[1], v[2]);
      if (columns_ == 6) part.normals.emplace_back(v[3], v[4], v[5]);
      ++added;
    }
    points_ += added;
    if (added == 0 && points_ == 0) throw file_error(path_, "no points");
    return added;
  }

 private:
  std::filesystem::path path_;
  io::FileWindow file_;
  std::size_t columns_ = 0;  // fixed by the first point line
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
