#include "pss/io/output_format.hpp"

#include <string>

#include "pss/core/error.hpp"
#include "text.hpp"

namespace pss {
namespace {

using io::lowercase_extension;

constexpr const char* kImageExtensions = ".png, .jpg, .jpeg or .exr";
constexpr const char* kPointsExtensions = ".ply or .xyz";
constexpr const char* kMeshExtensions = ".ply, .obj, .stl or .off";

// Says what the name should be, so that -o cloud.ply on `render` is no mystery.
[[noreturn]] void refuse(const std::filesystem::path& path, const std::string& what, const char* extensions) {
  const std::string ext = path.extension().string();
  throw file_error(path, "cannot write " + what + (ext.empty() ? " without an extension" : " as " + quote(ext)) +
                             ": name it " + extensions);
}

}  // namespace

ImageFormat image_format_of(const std::filesystem::path& path) {
  const std::string ext = lowercase_extension(path);
  if (ext == ".png") return ImageFormat::png;
  if (ext == ".jpg" || ext == ".jpeg") return ImageFormat::jpeg;
  if (ext == ".exr") return ImageFormat::exr;
  refuse(path, "an image", kImageExtensions);
}

PointsFormat points_format_of(const std::filesystem::path& path) {
  const std::string ext = lowercase_extension(path);
  if (ext == ".ply") return PointsFormat::ply;
  if (ext == ".xyz") return PointsFormat::xyz;
  refuse(path, "a point cloud", kPointsExtensions);
}

MeshFormat mesh_format_of(const std::filesystem::path& path) {
  const std::string ext = lowercase_extension(path);
  if (ext == ".ply") return MeshFormat::ply;
  if (ext == ".obj") return MeshFormat::obj;
  if (ext == ".stl") return MeshFormat::stl;
  if (ext == ".off") return MeshFormat::off;
  refuse(path, "a mesh", kMeshExtensions);
}

}  // namespace pss
