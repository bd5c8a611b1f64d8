// Reading back what `pss mesh` writes, independently of the writer: binary PLY (float or
// double positions, x y z nx ny nz, faces as uchar-counted int lists), OBJ (v, vn, f a//a),
// OFF and binary STL (its corners welded where they coincide exactly, as the mesh's shared
// vertices are written alike). Any surprise fails the calling test.
#pragma once

#include <filesystem>

#include "pss/mesh/triangle_mesh.hpp"

namespace pss::test {

// Positions far from zero (above 10⁴) come about the first vertex, in TriangleMesh::origin,
// so that those written in double keep their detail; normals are empty for OFF and STL.
TriangleMesh read_mesh(const std::filesystem::path& path);

}  // namespace pss::test
