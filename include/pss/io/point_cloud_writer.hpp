// A point cloud written a part at a time, in input order (issue 28: a cloud larger than
// memory is written as its parts are made). The whole-cloud writers (write_ply, write_xyz)
// write theirs as one part, so a cloud's bytes are the same either way.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include <glm/ext/vector_double3.hpp>

#include "pss/io/output_format.hpp"
#include "pss/io/ply.hpp"
#include "pss/points/cloud.hpp"

namespace pss {

// What a written cloud holds, known before its first point: a PLY header names its count and
// its properties.
struct PointsLayout {
  std::uint64_t count = 0;  // points in all
  glm::dvec3 origin{0.0};   // the parts' positions are about it (PointCloud::origin)
  bool normals = false, colors = false;
  std::vector<ScalarProperty> scalars;  // names and types; values ignored
  std::vector<std::string> extra;       // int properties (PLY only), e.g. "status"

  bool has_origin() const { return origin != glm::dvec3(0.0); }  // written in double
};

// The layout of `cloud` written whole with `extra` (write_ply's, write_point_cloud's).
PointsLayout layout_of(const PointCloud& cloud, std::span<const PlyIntProperty> extra = {});

// Each format writes what it has room for: PLY the whole layout, XYZ positions and normals.
// Every failure is a file_error(path, "cannot write: ..."), and nothing is left under the
// destination's name unless commit() succeeds (OutputFile).
class PointCloudWriter {
 public:
  // .ply or .xyz by extension, as write_point_cloud (points_format_of).
  PointCloudWriter(const std::filesystem::path& path, PointsLayout layout);
  // In `format` whatever the extension (write_ply, write_xyz). Refuses invalid or repeated
  // property names as write_ply does, then opens the OutputFile and writes the header.
  PointCloudWriter(const std::filesystem::path& path, PointsFormat format, PointsLayout layout);
  ~PointCloudWriter();
  PointCloudWriter(const PointCloudWriter&) = delete;
  PointCloudWriter& operator=(const PointCloudWriter&) = delete;

  // Appends the part's points after those before. The part holds at least what the layout
  // says, one per point: normals and colours where it has them, its scalars first (same names
  // and types, values that fit), and its origin is the layout's; `extra` is one span per
  // layout.extra name, in order. What else the part holds is not written (write_xyz's layout
  // leaves a cloud's colours and scalars out). More points than the layout's count throw.
  void append(const PointCloud& part, std::span<const PlyIntProperty> extra = {});
  // Throws unless the layout's count of points were appended; then commits the OutputFile.
  void commit();

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace pss
