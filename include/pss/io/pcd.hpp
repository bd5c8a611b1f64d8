// PCD point clouds, the Point Cloud Library's format (version 0.7 headers).
#pragma once

#include <filesystem>

#include "pss/points/cloud.hpp"

namespace pss {

// Reads DATA ascii, binary and binary_compressed (LZF, fields stored one after the other).
// Fields x y z are required; normal_x normal_y normal_z are taken when all three are there,
// and rgb or rgba (4 bytes packed 0x00RRGGBB, as a float or an integer) as colours. Any
// TYPE/SIZE (F4 F8, I1..I8, U1..U8); other fields, COUNT > 1 ones included, are skipped.
// Binary data is read as little-endian (PCL writes its machine's byte order, in practice
// always little). Points with a NaN coordinate (PCL's invalid points in organized clouds)
// are dropped with their normals and colours; VIEWPOINT is ignored (PCL does not apply it to
// the points either). Every problem is a one-line pss::Error naming the file.
PointCloud read_pcd(const std::filesystem::path& path);

}  // namespace pss
