// STL meshes (ASCII and binary) as point clouds: their vertices.
#pragma once

#include <filesystem>

#include "pss/points/cloud.hpp"

namespace pss {

// Binary when the file's size is exactly 84 + 50 × the facet count at byte 80 (binary files
// may begin with "solid" too), else ASCII, which must begin with "solid". A vertex shared by
// several facets is stored once per facet: the cloud keeps each exactly equal position once,
// in the order first seen. No normals: STL's are per facet, and a vertex's facets disagree
// (by 90° at a cube's corner), so none of them is the surface normal at the vertex; a cloud
// without normals gets them from the projection. Every problem is a one-line pss::Error.
PointCloud read_stl(const std::filesystem::path& path);

}  // namespace pss
