#include "pss/io/point_cloud_file.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "pss/core/error.hpp"
#include "pss/io/output_format.hpp"
#include "pss/io/las.hpp"
#include "pss/io/obj.hpp"
#include "pss/io/off.hpp"
#include "pss/io/pcd.hpp"
#include "pss/io/ply.hpp"
#include "pss/io/stl.hpp"
#include "pss/io/xyz.hpp"
#include "pss/io/volume_file.hpp"
#include "text.hpp"

namespace pss {

namespace {

using CloudReader = PointCloud (*)(const std::filesystem::path&);

// The reader of a point cloud format, by lowercase extension; null for none.
CloudReader cloud_reader(const std::string& ext) {
  if (ext == ".ply") return read_ply;
  // .pwn: CGAL's points with normals, x y z nx ny nz.
  if (ext == ".xyz" || ext == ".txt" || ext == ".pts" || ext == ".pwn") return read_xyz;
  if (ext == ".obj") return read_obj;
  if (ext == ".off") return read_off;
  if (ext == ".stl") return read_stl;
  if (ext == ".pcd") return read_pcd;
  if (ext == ".las") return read_las;
  return nullptr;
}

}  // namespace

bool is_point_cloud_file(const std::filesystem::path& path) {
  return cloud_reader(io::lowercase_extension(path)) != nullptr;
}

PointCloud read_point_cloud(const std::filesystem::path& path) {
  const std::string ext = io::lowercase_extension(path);
  if (const CloudReader read = cloud_reader(ext)) return read(path);
  if (ext == ".laz") throw file_error(path, "compressed LAS (LAZ) is not supported; decompress it to .las first (laszip, PDAL)");
  if (std::filesystem::is_directory(path)) throw file_error(path, "is a folder, not a point cloud file");
  if (ext == ".raw" || has_volume_header(path))
    throw file_error(path, "is a volume, not a point cloud (pss info, volume, extract and mesh read volumes; a raw "
                           "one with --dims XxYxZ)");
  throw file_error(path, "unknown point cloud format " + quote(path.extension().string()) +
                             " (expected .ply, .xyz, .txt, .pts, .pwn, .obj, .off, .stl, .pcd or .las)");
}

void write_point_cloud(const std::filesystem::path& path, const PointCloud& cloud,
                       std::span<const PlyIntProperty> extra) {
  switch (points_format_of(path)) {
    case PointsFormat::ply: return write_ply(path, cloud, extra);
    case PointsFormat::xyz: return write_xyz(path, cloud);
  }
}

void tidy_normals(PointCloud& cloud) {
  for (vec3& n : cloud.normals) n = is_finite(n) ? tidy_normal(n) : vec3(0.0f);
}

vec3 tidy_normal(vec3 n) {
  // In double: the squared length of a huge or tiny float normal over- or underflows.
  const double len2 = double(n.x) * n.x + double(n.y) * n.y + double(n.z) * n.z;
  // Already unit within rounding: leave the bits alone, so write/read round trips are exact.
  return len2 > 0.0 && std::abs(len2 - 1.0) > 1e-6 ? vec3(glm::dvec3(n) / std::sqrt(len2)) : n;
}

}  // namespace pss
