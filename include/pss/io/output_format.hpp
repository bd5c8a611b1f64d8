// What pss writes is what the output's name says: the format follows the extension
// (case-insensitive), and an extension pss does not write, or one of the wrong kind (a
// point cloud's for an image), is a one-line error naming the file.
#pragma once

#include <filesystem>

namespace pss {

enum class ImageFormat { png, jpeg, exr };
enum class PointsFormat { ply, xyz };
enum class MeshFormat { ply, obj, stl, off };

// .png, .jpg or .jpeg, .exr; anything else throws file_error(path, "cannot write: ...").
ImageFormat image_format_of(const std::filesystem::path& path);
// .ply, .xyz; anything else throws file_error(path, "cannot write: ...").
PointsFormat points_format_of(const std::filesystem::path& path);
// .ply, .obj, .stl, .off; anything else throws file_error(path, "cannot write: ...").
MeshFormat mesh_format_of(const std::filesystem::path& path);

}  // namespace pss
