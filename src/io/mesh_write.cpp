// write_mesh: PLY, OBJ, STL and OFF.
#include <algorithm>
#include <array>
#include <bit>
#include <cstdio>
#include <string>
#include <vector>

#include "pss/core/error.hpp"
#include "pss/io/mesh_file.hpp"
#include "pss/io/output_file.hpp"
#include "pss/io/output_format.hpp"

namespace pss {
namespace {

namespace fs = std::filesystem;

template <class T>
void put(std::string& out, T value) {
  auto raw = std::bit_cast<std::array<char, sizeof(T)>>(value);
  if (std::endian::native != std::endian::little) std::reverse(raw.begin(), raw.end());
  out.append(raw.data(), raw.size());
}

// Text in chunks of about this many bytes: one write each, never the whole file in memory.
constexpr std::size_t kChunk = 1 << 20;

void flush_if_full(std::string& buffer, std::ostream& out, bool last = false) {
  if (buffer.size() >= kChunk || last) {
    out.write(buffer.data(), std::streamsize(buffer.size()));
    buffer.clear();
  }
}

void printf_to(std::string& out, const char* format, auto... values) {
  char line[256];
  const int n = std::snprintf(line, sizeof line, format, values...);
  out.append(line, std::size_t(std::max(n, 0)));
}

glm::dvec3 world(const TriangleMesh& mesh, std::size_t i) { return mesh.origin + glm::dvec3(mesh.positions[i]); }

void write_ply(std::ostream& out, const TriangleMesh& mesh) {
  const bool recentred = mesh.origin != glm::dvec3(0.0);
  const std::size_t nv = mesh.positions.size();
  out << "ply\nformat binary_little_endian 1.0\ncomment written by pss\nelement vertex " << nv << "\n";
  for (const char* axis : {"x", "y", "z"}) out << "property " << (recentred ? "double " : "float ") << axis << "\n";
  out << "property float nx\nproperty float ny\nproperty float nz\nelement face " << mesh.triangles.size()
      << "\nproperty list uchar int vertex_indices\nend_header\n";
  std::string buffer;
  for (std::size_t i = 0; i < nv; ++i) {
    if (recentred) {
      const glm::dvec3 p = world(mesh, i);
      for (int k = 0; k < 3; ++k) put(buffer, p[k]);
    } else {
      for (int k = 0; k < 3; ++k) put(buffer, mesh.positions[i][k]);
    }
    for (int k = 0; k < 3; ++k) put(buffer, mesh.normals[i][k]);
    flush_if_full(buffer, out);
  }
  for (const auto& t : mesh.triangles) {
    put(buffer, std::uint8_t(3));
    for (int v : t) put(buffer, std::int32_t(v));
    flush_if_full(buffer, out);
  }
  flush_if_full(buffer, out, true);
}

void write_obj(std::ostream& out, const TriangleMesh& mesh) {
  const char* vertex = mesh.origin != glm::dvec3(0.0) ? "v %.17g %.17g %.17g\n" : "v %.9g %.9g %.9g\n";
  std::string buffer = "# written by pss\n";
  for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
    const glm::dvec3 p = world(mesh, i);
    printf_to(buffer, vertex, p.x, p.y, p.z);
    flush_if_full(buffer, out);
  }
  for (const vec3& n : mesh.normals) {
    printf_to(buffer, "vn %.9g %.9g %.9g\n", double(n.x), double(n.y), double(n.z));
    flush_if_full(buffer, out);
  }
  for (const auto& t : mesh.triangles) {  // OBJ counts from 1
    printf_to(buffer, "f %d//%d %d//%d %d//%d\n", t[0] + 1, t[0] + 1, t[1] + 1, t[1] + 1, t[2] + 1, t[2] + 1);
    flush_if_full(buffer, out);
  }
  flush_if_full(buffer, out, true);
}

void write_off(std::ostream& out, const TriangleMesh& mesh) {
  const char* vertex = mesh.origin != glm::dvec3(0.0) ? "%.17g %.17g %.17g\n" : "%.9g %.9g %.9g\n";
  std::string buffer;
  printf_to(buffer, "OFF\n%zu %zu 0\n", mesh.positions.size(), mesh.triangles.size());
  for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
    const glm::dvec3 p = world(mesh, i);
    printf_to(buffer, vertex, p.x, p.y, p.z);
    flush_if_full(buffer, out);
  }
  for (const auto& t : mesh.triangles) {
    printf_to(buffer, "3 %d %d %d\n", t[0], t[1], t[2]);
    flush_if_full(buffer, out);
  }
  flush_if_full(buffer, out, true);
}

// Binary STL: an 80-byte header, the count, then per triangle its unit normal, its three
// corners and two bytes of attributes (zero).
void write_stl(const fs::path& path, std::ostream& out, const TriangleMesh& mesh) {
  if (mesh.triangles.size() > 0xffffffffu) throw file_error(path, "cannot write: more than 2^32 triangles for STL");
  std::string buffer(80, '\0');
  std::copy_n("binary STL written by pss", 25, buffer.begin());
  put(buffer, std::uint32_t(mesh.triangles.size()));
  for (const auto& t : mesh.triangles) {
    const glm::dvec3 a = world(mesh, std::size_t(t[0])), b = world(mesh, std::size_t(t[1])),
                     c = world(mesh, std::size_t(t[2]));
    const glm::dvec3 cross = glm::cross(b - a, c - a);
    const double length = glm::length(cross);
    const glm::vec3 normal = length > 0 ? glm::vec3(cross / length) : glm::vec3(0.0f);
    for (int k = 0; k < 3; ++k) put(buffer, normal[k]);
    for (const glm::dvec3& p : {a, b, c})
      for (int k = 0; k < 3; ++k) put(buffer, float(p[k]));
    put(buffer, std::uint16_t(0));
    flush_if_full(buffer, out);
  }
  flush_if_full(buffer, out, true);
}

}  // namespace

void check_mesh_origin(const fs::path& path, const glm::dvec3& origin) {
  // STL holds world positions in float only: far from zero for its size (the origin is set
  // only then, point_cloud_file.hpp), the mesh would lose its detail or collapse.
  if (mesh_format_of(path) == MeshFormat::stl && origin != glm::dvec3(0.0))
    throw file_error(path, "cannot write: STL holds positions as floats, which would round away this mesh's detail "
                           "far from the origin (a georeferenced cloud); write .ply, .obj or .off");
}

void write_mesh(const fs::path& path, const TriangleMesh& mesh) {
  const MeshFormat format = mesh_format_of(path);
  check_mesh_origin(path, mesh.origin);
  if (mesh.normals.size() != mesh.positions.size())
    throw file_error(path, "cannot write: " + std::to_string(mesh.positions.size()) + " vertices but " +
                               std::to_string(mesh.normals.size()) + " normals");
  for (const auto& t : mesh.triangles)
    for (int v : t)
      if (v < 0 || std::size_t(v) >= mesh.positions.size())
        throw file_error(path, "cannot write: a triangle names vertex " + std::to_string(v) + " of " +
                                   std::to_string(mesh.positions.size()));
  OutputFile file(path);
  switch (format) {
    case MeshFormat::ply: write_ply(file.stream(), mesh); break;
    case MeshFormat::obj: write_obj(file.stream(), mesh); break;
    case MeshFormat::off: write_off(file.stream(), mesh); break;
    case MeshFormat::stl: write_stl(path, file.stream(), mesh); break;
  }
  file.commit();
}

}  // namespace pss
