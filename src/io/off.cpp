#include "pss/io/off.hpp"

#include <cmath>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "color.hpp"
#include "pss/core/error.hpp"
#include "pss/io/output_file.hpp"
#include "pss/io/point_cloud_file.hpp"
#include "text.hpp"

namespace pss {
namespace {

// What the header keyword says each vertex line holds after x y z.
struct OffLayout {
  bool texture = false, colors = false, normals = false;
};

// [ST][C][N]OFF, in that order; false for anything else.
bool parse_keyword(std::string_view word, OffLayout& layout, bool& other_dimension) {
  other_dimension = false;
  if (!word.ends_with("OFF")) return false;
  word.remove_suffix(3);
  const auto take = [&](std::string_view prefix) {
    if (!word.starts_with(prefix)) return false;
    word.remove_prefix(prefix.size());
    return true;
  };
  layout.texture = take("ST");
  layout.colors = take("C");
  layout.normals = take("N");
  other_dimension = take("4") || take("n");
  return word.empty() && !other_dimension;
}

// A colour channel: 0..1 where written as a fraction ("0.5", "1e0"), 0..255 otherwise.
std::uint8_t channel(std::string_view token, double value) {
  if (token.find_first_of(".eE") != std::string_view::npos) return io::channel_from_unit(value);
  return io::channel_from_unit(value / 255.0);
}

}  // namespace

PointCloud read_off(const std::filesystem::path& path) {
  const std::string file = read_file(path);
  io::Lines lines(file);
  std::string_view line;
  std::vector<std::string_view> words;
  const auto fail = [&](const std::string& problem) {
    return file_error(path, "line " + std::to_string(lines.number()) + ": " + problem);
  };
  // The next line with words on it, comments cut; false at the end of the file.
  const auto next_words = [&] {
    while (lines.next(line)) {
      words = io::split_words(line.substr(0, line.find('#')));
      if (!words.empty()) return true;
    }
    return false;
  };
  if (!next_words()) throw file_error(path, "empty OFF file");
  OffLayout layout;
  bool other_dimension = false;
  std::size_t first = 0;  // where the counts begin on this line
  if (parse_keyword(words[0], layout, other_dimension)) {
    first = 1;
  } else if (other_dimension) {
    throw fail(quote(words[0]) + ": only 3-dimensional OFF files are read");
  } else if (double v; !io::parse_number(words[0], v)) {
    throw fail("expected the keyword OFF (or COFF, NOFF, CNOFF, STOFF, ...), found " + quote(words[0], 40));
  }
  if (first == words.size()) {
    if (!next_words()) throw file_error(path, "no vertex count after " + quote("OFF"));
    first = 0;
  }
  if (words.size() - first < 2 || words.size() - first > 3)
    throw fail("expected the counts 'vertices faces [edges]'");
  std::uint64_t vertices = 0, faces = 0;
  for (std::size_t i = first; i < words.size(); ++i) {
    double v;
    // Compared before any cast: a count beyond uint64 (1e30, inf) is refused, not converted.
    if (!io::parse_number(words[i], v) || !(v >= 0) || v > 9e15 || v != std::floor(v))
      throw fail("malformed count " + quote(words[i], 40));
    if (i == first) vertices = std::uint64_t(v);
    if (i == first + 1) faces = std::uint64_t(v);
  }
  if (vertices == 0) throw fail("no vertices");

  const std::size_t normal_at = 3, color_at = layout.normals ? 6 : 3;
  const std::size_t fixed = color_at + (layout.texture ? 2 : 0);
  PointCloud cloud;
  cloud.mesh_vertices = faces > 0;
  std::vector<glm::dvec3> world;
  // The count may lie: nothing is reserved from it, and the lines must be there.
  for (std::uint64_t k = 0; k < vertices; ++k) {
    if (!next_words())
      throw file_error(path, "the header says " + std::to_string(vertices) + " vertices, the file has " +
                                 std::to_string(k));
    const std::size_t color_count = words.size() - std::min(words.size(), fixed);
    if (words.size() < fixed || (layout.colors ? color_count != 3 && color_count != 4 : color_count != 0))
      throw fail("expected " + std::to_string(fixed) + (layout.colors ? " + 3 or 4" : "") + " numbers per vertex, found " +
                 std::to_string(words.size()));
    double v[12];
    for (std::size_t i = 0; i < words.size(); ++i)
      if (!io::parse_number(words[i], v[i])) throw fail("malformed number " + quote(words[i], 40));
    world.emplace_back(v[0], v[1], v[2]);
    if (!is_finite(vec3(world.back()))) throw fail("non-finite coordinate");
    if (layout.normals) cloud.normals.emplace_back(glm::dvec3(v[normal_at], v[normal_at + 1], v[normal_at + 2]));
    if (layout.colors) {
      const std::size_t c = color_at;
      if (!is_finite(vec3(v[c], v[c + 1], v[c + 2]))) throw fail("non-finite colour");
      cloud.colors.emplace_back(channel(words[c], v[c]), channel(words[c + 1], v[c + 1]),
                                channel(words[c + 2], v[c + 2]));
    }
  }
  set_world_positions(cloud, world);
  tidy_normals(cloud);
  return cloud;
}

}  // namespace pss
