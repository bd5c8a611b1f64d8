// The formats that PointCloudWriter chooses among (internal to src/io): each one's header
// and records live beside its reader (ply_write.cpp, xyz.cpp).
#pragma once

#include <filesystem>
#include <memory>
#include <ostream>
#include <span>

#include "pss/io/point_cloud_writer.hpp"

namespace pss {

// One format's bytes. PointCloudWriter has checked each part against the layout (sizes,
// origin, count, the scalars' values) before write() sees it.
class PointsEncoder {
 public:
  virtual ~PointsEncoder() = default;
  virtual void write_header(std::ostream& out) = 0;
  virtual void write(std::ostream& out, const PointCloud& part, std::span<const PlyIntProperty> extra) = 0;
};

// Refuses invalid or repeated property names: file_error(path, "cannot write: ...").
std::unique_ptr<PointsEncoder> ply_encoder(const std::filesystem::path& path, const PointsLayout& layout);
std::unique_ptr<PointsEncoder> xyz_encoder(const PointsLayout& layout);

}  // namespace pss
