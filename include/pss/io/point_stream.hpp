// A point cloud file read a part at a time, front to back (issue 28): a cloud larger than
// memory is read this way, and the whole-file readers of the formats such clouds come in
// (read_ply, read_xyz, read_las) gather these parts.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <vector>

#include <glm/ext/vector_double3.hpp>

#include "pss/points/cloud.hpp"

namespace pss {

// Points of a file in its order: world positions as it gives them, and each other array one
// value per point, or empty where the file has none. The scalars' names and types are the
// file's (PointCloud::scalars); their values are this part's.
struct PointPart {
  std::vector<glm::dvec3> world;
  std::vector<vec3> normals;  // as the file gives them: not yet unit length (tidy_normals)
  std::vector<Rgb8> colors;
  std::vector<ScalarProperty> scalars;

  std::size_t size() const { return world.size(); }
  void clear();  // no points; the scalars keep their names and types
};

class PointStream {
 public:
  virtual ~PointStream() = default;
  // Appends the file's next points, at most `most`, to `part`; returns how many (0: the file
  // has no more). A malformed or truncated file throws a one-line file_error when its
  // fault is reached.
  virtual std::size_t read(PointPart& part, std::size_t most) = 0;
  // The file's point count where its header gives one (PLY, LAS), else 0 (XYZ).
  virtual std::uint64_t declared_count() const = 0;
  // Whether floats hold every position exactly (a PLY of float coordinates): a whole read
  // keeps them at half the memory of doubles.
  virtual bool float_positions() const { return false; }
  // Whether the points are a mesh's vertices (PointCloud::mesh_vertices).
  virtual bool mesh_vertices() const { return false; }
};

// Whether open_point_stream reads the file's format.
bool has_point_stream(const std::filesystem::path& path);

// .ply, .xyz (.txt, .pts, .pwn) or .las, by extension in any case; a file_error for other formats.
std::unique_ptr<PointStream> open_point_stream(const std::filesystem::path& path);

// Every point of `stream` in one cloud (the whole-file readers): positions about the origin
// they choose (local_origin), normals tidied (tidy_normals).
PointCloud read_all(PointStream& stream);

}  // namespace pss
