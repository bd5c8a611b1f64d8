#include "support/mesh_readers.hpp"

#include <gtest/gtest.h>

#include <cctype>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <tuple>

namespace pss::test {

namespace {

std::string bytes_of(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

template <class T>
T take(const std::string& b, std::size_t& at) {
  T v;
  EXPECT_LE(at + sizeof(T), b.size()) << "truncated";
  if (at + sizeof(T) > b.size()) return T{};
  std::memcpy(&v, b.data() + at, sizeof(T));
  at += sizeof(T);
  return v;
}

// Positions far from zero (a georeferenced mesh's, in double) are kept about the first one,
// in TriangleMesh::origin, so that floats keep their detail.
void about_an_origin(const std::vector<glm::dvec3>& world, TriangleMesh& m) {
  if (!world.empty() && glm::length(world[0]) > 1e4) m.origin = world[0];
  for (const glm::dvec3& p : world) m.positions.push_back(vec3(p - m.origin));
}

TriangleMesh read_ply(const std::string& b) {
  TriangleMesh m;
  const std::size_t end = b.find("end_header\n");
  EXPECT_NE(end, std::string::npos);
  std::istringstream header(b.substr(0, end));
  std::string line;
  std::size_t vertices = 0, faces = 0;
  bool doubles = false;
  while (std::getline(header, line)) {
    if (line.rfind("element vertex ", 0) == 0) vertices = std::stoul(line.substr(15));
    if (line.rfind("element face ", 0) == 0) faces = std::stoul(line.substr(13));
    if (line == "property double x") doubles = true;
  }
  EXPECT_NE(b.find("format binary_little_endian 1.0"), std::string::npos);
  EXPECT_NE(b.find("property float nx\nproperty float ny\nproperty float nz\nelement face"), std::string::npos);
  EXPECT_NE(b.find("property list uchar int vertex_indices\nend_header"), std::string::npos);
  std::size_t at = end + 11;
  std::vector<glm::dvec3> world;
  for (std::size_t i = 0; i < vertices; ++i) {
    glm::dvec3 p;
    for (int k = 0; k < 3; ++k) p[k] = doubles ? take<double>(b, at) : double(take<float>(b, at));
    vec3 n;
    for (int k = 0; k < 3; ++k) n[k] = take<float>(b, at);
    world.push_back(p);
    m.normals.push_back(n);
  }
  about_an_origin(world, m);
  for (std::size_t i = 0; i < faces; ++i) {
    EXPECT_EQ(take<std::uint8_t>(b, at), 3);
    std::array<int, 3> t;
    for (int& v : t) v = take<std::int32_t>(b, at);
    m.triangles.push_back(t);
  }
  EXPECT_EQ(at, b.size()) << "bytes after the faces";
  return m;
}

TriangleMesh read_obj(const std::string& b) {
  TriangleMesh m;
  std::vector<glm::dvec3> world;
  std::istringstream in(b);
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream words(line);
    std::string kind;
    words >> kind;
    if (kind == "v" || kind == "vn") {
      glm::dvec3 p;
      words >> p.x >> p.y >> p.z;
      if (kind == "v") world.push_back(p);
      else m.normals.push_back(vec3(p));
    } else if (kind == "f") {
      std::array<int, 3> t;
      for (int& v : t) {
        std::string corner;
        words >> corner;
        const std::size_t slashes = corner.find("//");
        EXPECT_NE(slashes, std::string::npos) << corner;
        v = std::stoi(corner.substr(0, slashes)) - 1;
        EXPECT_EQ(corner.substr(slashes + 2), std::to_string(v + 1));
      }
      m.triangles.push_back(t);
    }
  }
  about_an_origin(world, m);
  return m;
}

TriangleMesh read_off(const std::string& b) {
  TriangleMesh m;
  std::istringstream in(b);
  std::string magic;
  std::size_t vertices = 0, faces = 0, edges = 0;
  in >> magic >> vertices >> faces >> edges;
  EXPECT_EQ(magic, "OFF");
  std::vector<glm::dvec3> world(vertices);
  for (glm::dvec3& p : world) in >> p.x >> p.y >> p.z;
  about_an_origin(world, m);
  m.triangles.resize(faces);
  for (auto& t : m.triangles) {
    int count = 0;
    in >> count >> t[0] >> t[1] >> t[2];
    EXPECT_EQ(count, 3);
  }
  EXPECT_FALSE(in.fail());
  return m;
}

TriangleMesh read_stl(const std::string& b) {
  TriangleMesh m;
  std::size_t at = 80;
  const std::uint32_t count = take<std::uint32_t>(b, at);
  EXPECT_EQ(b.size(), 84 + 50 * std::size_t(count));
  std::map<std::tuple<float, float, float>, int> welded;
  for (std::uint32_t i = 0; i < count; ++i) {
    for (int k = 0; k < 3; ++k) take<float>(b, at);  // the facet normal
    std::array<int, 3> t;
    for (int& v : t) {
      vec3 p;
      for (int k = 0; k < 3; ++k) p[k] = take<float>(b, at);
      const auto [it, added] = welded.try_emplace({p.x, p.y, p.z}, int(m.positions.size()));
      if (added) m.positions.push_back(p);
      v = it->second;
    }
    take<std::uint16_t>(b, at);
    m.triangles.push_back(t);
  }
  return m;
}

}  // namespace

TriangleMesh read_mesh(const std::filesystem::path& path) {
  const std::string b = bytes_of(path);
  std::string ext = path.extension().string();
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  TriangleMesh m;
  if (ext == ".ply") m = read_ply(b);
  else if (ext == ".obj") m = read_obj(b);
  else if (ext == ".off") m = read_off(b);
  else if (ext == ".stl") m = read_stl(b);
  else ADD_FAILURE() << "no reader for " << path;
  for (const auto& t : m.triangles)
    for (int v : t)
      if (v < 0 || std::size_t(v) >= m.positions.size()) {
        ADD_FAILURE() << path << ": a face names vertex " << v << " of " << m.positions.size();
        return {};
      }
  return m;
}

ScanMesh read_scan_mesh(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::size_t vertices = 0, faces = 0;
  bool ascii = false;
  for (std::string line; std::getline(in, line) && line != "end_header";) {
    if (line.rfind("element vertex ", 0) == 0) vertices = std::stoul(line.substr(15));
    if (line.rfind("element face ", 0) == 0) faces = std::stoul(line.substr(13));
    ascii = ascii || line.rfind("format ascii", 0) == 0;
  }
  ScanMesh m;
  for (std::size_t i = 0; i < vertices; ++i) {
    float p[3];
    if (ascii) {  // x y z first, then whatever else the line holds (the bunny's confidence, intensity)
      std::string line;
      std::getline(in, line);
      std::istringstream(line) >> p[0] >> p[1] >> p[2];
    } else {
      in.read(reinterpret_cast<char*>(p), sizeof p);
    }
    m.positions.push_back(glm::dvec3(p[0], p[1], p[2]));
  }
  m.normals.assign(vertices, glm::dvec3(0.0));
  for (std::size_t f = 0; f < faces; ++f) {
    int count = 0;
    std::int32_t v[3];
    if (ascii) {
      in >> count >> v[0] >> v[1] >> v[2];
    } else {
      unsigned char byte = 0;
      in.read(reinterpret_cast<char*>(&byte), 1);
      in.read(reinterpret_cast<char*>(v), sizeof v);
      count = byte;
    }
    EXPECT_EQ(count, 3);
    const glm::dvec3 a = m.positions[std::size_t(v[0])], b = m.positions[std::size_t(v[1])],
                     c = m.positions[std::size_t(v[2])];
    for (const int k : v) m.normals[std::size_t(k)] += glm::cross(b - a, c - a);
  }
  EXPECT_TRUE(in.good()) << path;
  return m;
}


}  // namespace pss::test
