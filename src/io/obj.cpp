#include "pss/io/obj.hpp"

#include <charconv>
#include <cstdint>
#include <optional>
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

// A face corner's vertex and normal, as indices into the file's v and vn lists.
struct Corner {
  std::size_t vertex, normal;
};

// OBJ indices count from 1, or back from the last element defined so far when negative;
// nullopt when the token is malformed or names an element not defined before it.
std::optional<std::size_t> resolve_index(std::string_view token, std::size_t defined) {
  std::int64_t i = 0;
  const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), i);
  if (ec != std::errc() || end != token.data() + token.size()) return std::nullopt;
  if (i > 0 && std::uint64_t(i) <= defined) return std::size_t(i - 1);
  if (i < 0 && i >= -std::int64_t(defined)) return std::size_t(std::int64_t(defined) + i);
  return std::nullopt;
}

}  // namespace

PointCloud read_obj(const std::filesystem::path& path) {
  const std::string file = read_file(path);
  io::Lines lines(file);
  PointCloud cloud;
  std::vector<glm::dvec3> world;
  bool every_vertex_colored = true;
  std::vector<vec3> normals;    // the vn statements, in order
  std::vector<Corner> corners;  // face corners that name a normal
  std::string_view line;
  while (lines.next(line)) {
    const auto fail = [&](const std::string& problem) {
      return file_error(path, "line " + std::to_string(lines.number()) + ": " + problem);
    };
    line = line.substr(0, line.find('#'));
    if (line.ends_with('\\')) throw fail("line continuations ('\\') are not supported");
    const std::vector<std::string_view> words = io::split_words(line);
    if (words.empty()) continue;
    const auto numbers = [&](double* v) {
      for (std::size_t i = 1; i < words.size(); ++i)
        if (!io::parse_number(words[i], v[i - 1])) throw fail("malformed number " + quote(words[i]));
    };
    if (words[0] == "v") {
      if (words.size() != 4 && words.size() != 5 && words.size() != 7)
        throw fail("expected 'v x y z [w]' or 'v x y z r g b', found " + std::to_string(words.size() - 1) +
                   " numbers");
      double v[6];
      numbers(v);
      world.emplace_back(v[0], v[1], v[2]);
      if (!is_finite(vec3(world.back()))) throw fail("non-finite coordinate");
      if (words.size() == 7 && every_vertex_colored) {
        if (!is_finite(vec3(v[3], v[4], v[5]))) throw fail("non-finite colour");
        cloud.colors.emplace_back(io::channel_from_unit(v[3]), io::channel_from_unit(v[4]),
                                  io::channel_from_unit(v[5]));
      } else {
        every_vertex_colored = false;
        cloud.colors.clear();
      }
    } else if (words[0] == "vn") {
      if (words.size() != 4) throw fail("expected 'vn x y z', found " + std::to_string(words.size() - 1) + " numbers");
      double n[3];
      numbers(n);
      normals.emplace_back(glm::dvec3(n[0], n[1], n[2]));  // a non-finite one has no direction (tidy_normals)
    } else if (words[0] == "f") {
      cloud.mesh_vertices = true;
      for (std::size_t i = 1; i < words.size(); ++i) {
        // v, v/vt, v/vt/vn or v//vn: only corners with a normal matter.
        const std::string_view corner = words[i];
        const std::size_t first = corner.find('/');
        const std::size_t second = first == std::string_view::npos ? first : corner.find('/', first + 1);
        if (second == std::string_view::npos) continue;
        const std::optional<std::size_t> vertex = resolve_index(corner.substr(0, first), world.size());
        const std::optional<std::size_t> normal = resolve_index(corner.substr(second + 1), normals.size());
        if (!vertex || !normal)
          throw fail("face corner " + quote(corner) + " names a " + (vertex ? "normal" : "vertex") +
                     " not defined before it");
        corners.push_back({*vertex, *normal});
      }
    }
  }
  if (world.empty()) throw file_error(path, "no vertices");
  set_world_positions(cloud, world);
  if (!corners.empty()) {
    // Zero where no face gives one: tidy_normals' "no direction".
    cloud.normals.assign(cloud.size(), vec3(0.0f));
    std::vector<bool> assigned(cloud.size(), false);
    for (const Corner& c : corners) {
      if (assigned[c.vertex]) continue;  // the first face to name a vertex wins
      cloud.normals[c.vertex] = normals[c.normal];
      assigned[c.vertex] = true;
    }
  } else if (normals.size() == cloud.size()) {
    cloud.normals = std::move(normals);
  }
  tidy_normals(cloud);
  return cloud;
}

}  // namespace pss
