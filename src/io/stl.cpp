#include "pss/io/stl.hpp"

#include <bit>
#include <cstdint>
#include <functional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "bytes.hpp"
#include "pss/core/error.hpp"
#include "pss/io/output_file.hpp"
#include "text.hpp"

namespace pss {
namespace {

namespace fs = std::filesystem;

// Collects vertices, each exactly equal position once, in first-seen order; in double, so
// that an ASCII file far from zero keeps its digits (points/cloud.hpp).
class UniqueVertices {
 public:
  void add(glm::dvec3 p) {
    p += glm::dvec3(0.0);  // -0 becomes +0: equal positions, one key
    const Key key{std::bit_cast<std::uint64_t>(p.x), std::bit_cast<std::uint64_t>(p.y),
                  std::bit_cast<std::uint64_t>(p.z)};
    if (index_.emplace(key, world_.size()).second) world_.push_back(p);
  }
  PointCloud take() {
    PointCloud cloud;
    set_world_positions(cloud, world_);
    return cloud;
  }

 private:
  struct Key {
    std::uint64_t x, y, z;
    bool operator==(const Key&) const = default;
  };
  struct Hash {
    std::size_t operator()(const Key& k) const {
      return std::hash<std::uint64_t>()((k.x * 0x9E3779B97F4A7C15ull ^ k.y) * 0x9E3779B97F4A7C15ull ^ k.z);
    }
  };
  std::unordered_map<Key, std::size_t, Hash> index_;
  std::vector<glm::dvec3> world_;
};

constexpr std::size_t kBinaryHeader = 84, kFacetBytes = 50;
constexpr bool kSwap = std::endian::native != std::endian::little;  // binary STL is little-endian

// The facet count at byte 80 (the file must be at least kBinaryHeader long).
std::uint64_t binary_facets(std::string_view file) { return io::load<std::uint32_t>(file.data() + 80, kSwap); }

PointCloud read_binary(const fs::path& path, std::string_view file, std::uint64_t facets) {
  UniqueVertices vertices;
  for (std::uint64_t f = 0; f < facets; ++f) {
    const char* facet = file.data() + kBinaryHeader + f * kFacetBytes;
    for (int corner = 0; corner < 3; ++corner) {
      const char* xyz = facet + 12 * (corner + 1);  // after the facet normal
      const vec3 p(io::load<float>(xyz, kSwap), io::load<float>(xyz + 4, kSwap), io::load<float>(xyz + 8, kSwap));
      if (!is_finite(p)) throw file_error(path, "facet " + std::to_string(f) + " has a non-finite coordinate");
      vertices.add(glm::dvec3(p));
    }
  }
  return vertices.take();
}

// solid NAME, then facets (facet normal .. / outer loop / 3 × vertex x y z / endloop /
// endfacet), then endsolid NAME; several solids may follow each other.
PointCloud read_ascii(const fs::path& path, std::string_view file) {
  UniqueVertices vertices;
  io::Lines lines(file);
  enum class In { nothing, solid, facet, loop } in = In::nothing;
  int corners = 0;
  std::string_view line;
  while (lines.next(line)) {
    const auto fail = [&](const std::string& problem) {
      return file_error(path, "line " + std::to_string(lines.number()) + ": " + problem);
    };
    const std::vector<std::string_view> words = io::split_words(line);
    if (words.empty()) continue;
    const std::string_view word = words[0];
    // Each keyword is valid in one place only; anything else is not STL.
    const auto expect = [&](In where, In next) {
      if (in != where) throw fail("unexpected " + quote(word));
      in = next;
    };
    if (word == "solid") expect(In::nothing, In::solid);
    else if (word == "endsolid") expect(In::solid, In::nothing);
    else if (word == "facet") expect(In::solid, In::facet);
    else if (word == "outer") expect(In::facet, In::loop), corners = 0;
    else if (word == "endfacet") expect(In::facet, In::solid);
    else if (word == "endloop") {
      if (corners != 3) throw fail("a facet has " + std::to_string(corners) + " vertices, not 3");
      expect(In::loop, In::facet);
    } else if (word == "vertex") {
      if (in != In::loop) throw fail("unexpected 'vertex'");
      if (words.size() != 4) throw fail("expected 'vertex x y z'");
      double v[3];
      for (int k = 0; k < 3; ++k)
        if (!io::parse_number(words[k + 1], v[k])) throw fail("malformed number " + quote(words[k + 1]));
      const glm::dvec3 p(v[0], v[1], v[2]);
      if (!is_finite(vec3(p))) throw fail("non-finite coordinate");
      vertices.add(p);
      ++corners;
    } else {
      throw fail("unexpected " + quote(word));
    }
  }
  if (in != In::nothing) throw file_error(path, "truncated: the file ends inside a solid (no 'endsolid')");
  return vertices.take();
}

}  // namespace

PointCloud read_stl(const fs::path& path) {
  const std::string file = read_file(path);
  const bool long_enough = file.size() >= kBinaryHeader;
  PointCloud cloud;
  if (long_enough && kBinaryHeader + binary_facets(file) * kFacetBytes == file.size()) {
    cloud = read_binary(path, file, binary_facets(file));
  } else {
    // Text, and begins with "solid" (binary headers may too, so a NUL byte says binary).
    const std::vector<std::string_view> first = io::split_words(std::string_view(file).substr(0, file.find('\n')));
    if (first.empty() || first[0] != "solid" || file.find('\0') != std::string::npos) {
      if (!long_enough) throw file_error(path, "not an STL file (too short for binary, no 'solid' for ASCII)");
      throw file_error(path, "not an STL file, or a truncated binary one: " + std::to_string(file.size()) +
                                 " bytes, but 84 + 50 x " + std::to_string(binary_facets(file)) + " facets = " +
                                 std::to_string(kBinaryHeader + binary_facets(file) * kFacetBytes));
    }
    cloud = read_ascii(path, file);
  }
  if (cloud.positions.empty()) throw file_error(path, "no facets");
  cloud.mesh_vertices = true;
  return cloud;
}

}  // namespace pss
