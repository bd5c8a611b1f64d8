// Reading and writing a point cloud whatever its file format, chosen by extension.
#pragma once

#include <filesystem>
#include <span>

#include "pss/io/ply.hpp"
#include "pss/points/cloud.hpp"

namespace pss {

// By extension, in any case: .ply → read_ply; .xyz, .txt, .pts, .pwn → read_xyz; .obj →
// read_obj; .off → read_off; .stl → read_stl; .pcd → read_pcd; .las → read_las. Anything
// else (.laz included: LAZ is not supported) is a file_error naming the formats we know.
PointCloud read_point_cloud(const std::filesystem::path& path);

// Whether read_point_cloud reads `path` by its extension.
bool is_point_cloud_file(const std::filesystem::path& path);

// .ply → write_ply with the extra properties; .xyz → write_xyz, which has no room for them
// (case-insensitive); anything else is a file_error (points_format_of).
void write_point_cloud(const std::filesystem::path& path, const PointCloud& cloud,
                       std::span<const PlyIntProperty> extra = {});

// The readers' common normal policy. Normals become unit length; zero ones stay zero (no
// direction to recover, and dropping one would misalign the arrays), and non-finite ones
// (PCL writes NaN where it fitted none) become zero: the file's normals are then left out
// and estimated, and the summaries say why (points/sample_normals.hpp: file_normals).
void tidy_normals(PointCloud& cloud);
// One finite normal as tidy_normals leaves it.
vec3 tidy_normal(vec3 n);

}  // namespace pss
