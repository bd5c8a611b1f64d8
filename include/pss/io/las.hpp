// LAS point clouds (ASPRS LAS 1.0-1.4, the lidar exchange format), uncompressed.
#pragma once

#include <filesystem>

#include "pss/points/cloud.hpp"

namespace pss {

// Reads point data record formats 0-10: X Y Z × scale + offset, the RGB of formats 2, 3,
// 5, 7, 8 and 10, and every format's intensity and classification as the scalar properties
// 'intensity' (uint16) and 'classification' (uint8: the ASPRS class, without format 0-5's
// flag bits). Colours are 16-bit in LAS, but many writers store 8-bit values unscaled:
// when no channel in the file exceeds 255 they are taken as they are, else scaled to 8 bits.
// Records longer than their format (extra bytes) are read at the header's length. The point
// count is LAS 1.4's 64-bit one where the header has it, else the legacy 32-bit one.
// Positions become float: georeferenced coordinates keep about 7 significant digits (a step
// of 0.5 m at 5,000,000 m); compressed LAS (LAZ) is refused. Every problem is a one-line
// pss::Error naming the file.
PointCloud read_las(const std::filesystem::path& path);

}  // namespace pss
