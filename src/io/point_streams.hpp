// The streams of each format that open_point_stream chooses among (internal to src/io).
#pragma once

#include <filesystem>
#include <memory>

#include "pss/io/point_stream.hpp"

namespace pss {

std::unique_ptr<PointStream> open_ply_stream(const std::filesystem::path& path);
std::unique_ptr<PointStream> open_xyz_stream(const std::filesystem::path& path);
std::unique_ptr<PointStream> open_las_stream(const std::filesystem::path& path);

}  // namespace pss
