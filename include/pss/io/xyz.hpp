// Plain-text point lists: one point per line, "x y z" or "x y z nx ny nz", separated by
// spaces, tabs or commas; '#' lines and blank lines are skipped.
#pragma once

#include <filesystem>

#include "pss/points/cloud.hpp"

namespace pss {

// Every line must hold the same count (3 or 6). Problems are one-line pss::Errors
// "FILE: line N: problem".
PointCloud read_xyz(const std::filesystem::path& path);

}  // namespace pss
