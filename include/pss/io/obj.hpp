// Wavefront OBJ meshes as point clouds: the vertices, with the normals and colours the file
// gives them.
#pragma once

#include <filesystem>

#include "pss/points/cloud.hpp"

namespace pss {

// Reads the `v x y z [w]` vertices (w ignored); `v x y z r g b` (r g b in 0..1) gives
// colours when every vertex has them. Normals: OBJ indexes `vn` from faces, so a vertex gets
// the normal of the first `f v/vt/vn` or `f v//vn` that names it (zero where none does);
// without face normal indices, as many `vn` as `v` pair by order; otherwise there are none.
// Other statements (vt, g, o, s, usemtl, faces without normals, ...) are ignored; a `\`
// line continuation is an error. Every problem is a one-line pss::Error "FILE: line N: ...".
PointCloud read_obj(const std::filesystem::path& path);

}  // namespace pss
