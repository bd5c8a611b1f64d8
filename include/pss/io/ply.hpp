// PLY point clouds: a lean reader for the formats real scanners and tools write, and a
// binary writer whose output opens in Open3D, PCL and MeshLab.
#pragma once

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>

#include "pss/points/cloud.hpp"

namespace pss {

// Reads the 'vertex' element's x y z (any scalar type) and, when all three are present,
// nx ny nz and red green blue (or diffuse_red ...): uchar colours as they are, float ones
// from 0..1, 16-bit ones from 0..65535, other integers as 0..255 (clamped). Its other scalar
// properties (intensity, confidence, a label, alpha) become PointCloud::scalars with their
// types, in header order: the first 64, each name once; an ASCII value that does not fit its
// type ("3.5" for an int) is an error, and a float one is rounded to float. List properties
// and other elements are skipped. Every problem is a one-line pss::Error "FILE: problem".
PointCloud read_ply(const std::filesystem::path& path);

// An extra per-vertex 'int' property, e.g. a label per point; values.size() == cloud size.
struct PlyIntProperty {
  std::string name;
  std::span<const std::int32_t> values;
};

// binary_little_endian: float x y z, float nx ny nz if the cloud has normals, uchar red
// green blue if it has colours, the cloud's scalars in their types, then each extra property
// as int. A scalar named like an extra property is written as input_NAME (pss project's
// 'status' beside an input's own); any other name written twice, a blank in a name, or a value
// that does not fit its type is a file_error. Written atomically (OutputFile).
void write_ply(const std::filesystem::path& path, const PointCloud& cloud,
               std::span<const PlyIntProperty> extra = {});

}  // namespace pss
