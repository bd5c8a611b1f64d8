#include "pss/io/point_stream.hpp"

#include <string>

#include "pss/core/error.hpp"
#include "pss/io/point_cloud_file.hpp"
#include "point_streams.hpp"
#include "text.hpp"

namespace pss {

void PointPart::clear() {
  world.clear();
  normals.clear();
  colors.clear();
  for (ScalarProperty& s : scalars) s.values.clear();
}

bool has_point_stream(const std::filesystem::path& path) {
  const std::string ext = io::lowercase_extension(path);
  return ext == ".ply" || ext == ".xyz" || ext == ".txt" || ext == ".pts" || ext == ".pwn" || ext == ".las";
}

std::unique_ptr<PointStream> open_point_stream(const std::filesystem::path& path) {
  const std::string ext = io::lowercase_extension(path);
  if (ext == ".ply") return open_ply_stream(path);
  if (ext == ".xyz" || ext == ".txt" || ext == ".pts" || ext == ".pwn") return open_xyz_stream(path);
  if (ext == ".las") return open_las_stream(path);
  throw file_error(path, "cannot be read a part at a time: " + quote(path.extension().string()) +
                             " is not .ply, .xyz, .txt, .pts, .pwn or .las");
}

PointCloud read_all(PointStream& stream) {
  constexpr std::size_t kPart = std::size_t(1) << 16;
  const std::uint64_t expected = stream.declared_count();
  const bool floats = stream.float_positions();
  std::vector<glm::dvec3> world;
  std::vector<vec3> world_floats;
  if (floats) world_floats.reserve(expected);
  else world.reserve(expected);
  PointCloud cloud;
  PointPart part;
  for (bool first = true; stream.read(part, kPart) > 0; first = false) {
    if (first) {
      if (!part.normals.empty()) cloud.normals.reserve(expected);
      if (!part.colors.empty()) cloud.colors.reserve(expected);
      for (const ScalarProperty& s : part.scalars) {
        cloud.scalars.push_back({s.name, s.type, {}});
        cloud.scalars.back().values.reserve(expected);
      }
    }
    if (floats)
      for (const glm::dvec3& p : part.world) world_floats.push_back(vec3(p));
    else
      world.insert(world.end(), part.world.begin(), part.world.end());
    cloud.normals.insert(cloud.normals.end(), part.normals.begin(), part.normals.end());
    cloud.colors.insert(cloud.colors.end(), part.colors.begin(), part.colors.end());
    for (std::size_t k = 0; k < part.scalars.size(); ++k)
      cloud.scalars[k].values.insert(cloud.scalars[k].values.end(), part.scalars[k].values.begin(),
                                     part.scalars[k].values.end());
    part.clear();
  }
  cloud.mesh_vertices = stream.mesh_vertices();
  if (floats) set_world_positions(cloud, std::move(world_floats));
  else set_world_positions(cloud, world);
  tidy_normals(cloud);
  return cloud;
}

}  // namespace pss
