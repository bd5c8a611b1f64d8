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
// from 0..1, 16-bit ones from 0..65535, other integers as 0..255 (clamped). Other
// properties and elements are skipped. Every problem is a one-line pss::Error "FILE: problem".
PointCloud read_ply(const std::filesystem::path& path);

// An extra per-vertex 'int' property, e.g. a label per point; values.size() == cloud size.
struct PlyIntProperty {
  std::string name;
  std::span<const std::int32_t> values;
};

// binary_little_endian: float x y z, float nx ny nz if the cloud has normals, uchar red
// green blue if it has colours, then each extra property as int. Written atomically (OutputFile).
void write_ply(const std::filesystem::path& path, const PointCloud& cloud,
               std::span<const PlyIntProperty> extra = {});

}  // namespace pss
