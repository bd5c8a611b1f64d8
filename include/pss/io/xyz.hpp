// Plain-text point lists: one point per line, "x y z" or "x y z nx ny nz", separated by
// spaces, tabs or commas; '#' lines and blank lines are skipped.
#pragma once

#include <filesystem>

#include "pss/points/cloud.hpp"

namespace pss {

// Every line must hold the same count (3 or 6). Problems are one-line pss::Errors
// "FILE: line N: problem".
PointCloud read_xyz(const std::filesystem::path& path);

// One point a line, "x y z" or with normals "x y z nx ny nz", each float as %.9g: nine
// significant digits read back as the same float. Written atomically (OutputFile).
void write_xyz(const std::filesystem::path& path, const PointCloud& cloud);

}  // namespace pss
