// Reading back what `pss mesh` writes, independently of the writer: binary PLY (float or
// double positions, x y z nx ny nz, faces as uchar-counted int lists), OBJ (v, vn, f a//a),
// OFF and binary STL (its corners welded where they coincide exactly, as the mesh's shared
// vertices are written alike). Any surprise fails the calling test.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "pss/mesh/triangle_mesh.hpp"

namespace pss::test {

// Positions far from zero (above 10⁴) come about the first vertex, in TriangleMesh::origin,
// so that those written in double keep their detail; normals are empty for OFF and STL.
TriangleMesh read_mesh(const std::filesystem::path& path);

// The vertices of a binary little-endian PLY of float x y z and faces of 3 int indices (the
// dragon's, as VCG writes it), or of an ASCII PLY whose vertex lines begin x y z (the
// bunny's), each with the area-weighted normal of its faces: a scan's truth for the normals
// of its points.
struct ScanMesh {
  std::vector<glm::dvec3> positions, normals;
};
ScanMesh read_scan_mesh(const std::string& path);

}  // namespace pss::test
