// Writing a triangle mesh in the format its name says (output_format.hpp's mesh_format_of):
// binary PLY with vertex normals (what MeshLab, Open3D, CloudCompare and Blender read best),
// OBJ with vertex normals, binary STL (facet normals, no shared vertices, as STL is), OFF.
// Written atomically (OutputFile). A mesh away from the world's origin (TriangleMesh::origin)
// is written with the origin added: in double in PLY, in 17 digits in OBJ and OFF; STL, which
// holds floats only, is refused for it (file_error).
#pragma once

#include <filesystem>

#include "pss/mesh/triangle_mesh.hpp"

namespace pss {

void write_mesh(const std::filesystem::path& path, const TriangleMesh& mesh);

// The refusal write_mesh gives a mesh about `origin` in `path`'s format, before the work: a
// georeferenced cloud's mesh cannot go to STL (file_error naming `path`).
void check_mesh_origin(const std::filesystem::path& path, const glm::dvec3& origin);

}  // namespace pss
