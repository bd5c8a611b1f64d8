#include "pss/io/point_cloud_writer.hpp"

#include <string>
#include <utility>

#include "pss/core/error.hpp"
#include "pss/io/output_file.hpp"
#include "ply_types.hpp"
#include "point_encoders.hpp"

namespace pss {
namespace {

namespace fs = std::filesystem;

std::unique_ptr<PointsEncoder> encoder_of(const fs::path& path, PointsFormat format, const PointsLayout& layout) {
  switch (format) {
    case PointsFormat::ply: return ply_encoder(path, layout);
    case PointsFormat::xyz: return xyz_encoder(layout);
  }
  return nullptr;
}

// (x, y, z) in the digits that read back as the same doubles.
std::string point_text(const glm::dvec3& p) {
  std::string text;
  for (int k = 0; k < 3; ++k) text.append(k == 0 ? "(" : ", ").append(io::text_of(p[k]));
  return text.append(")");
}

}  // namespace

PointsLayout layout_of(const PointCloud& cloud, std::span<const PlyIntProperty> extra) {
  PointsLayout layout{cloud.size(), cloud.origin, cloud.has_normals(), cloud.has_colors(), {}, {}};
  for (const ScalarProperty& s : cloud.scalars) layout.scalars.push_back({s.name, s.type, {}});
  for (const PlyIntProperty& p : extra) layout.extra.push_back(p.name);
  return layout;
}

// Members in this order: the encoder checks the names before the OutputFile is created.
struct PointCloudWriter::State {
  State(const fs::path& path, PointsFormat format, PointsLayout layout)
      : path(path), layout(std::move(layout)), encoder(encoder_of(path, format, this->layout)), file(path) {
    encoder->write_header(file.stream());
  }

  [[noreturn]] void fail(const std::string& problem) const { throw file_error(path, "cannot write: " + problem); }
  void check(const PointCloud& part, std::span<const PlyIntProperty> extra) const;
  void check_size(std::size_t n, std::size_t values, const std::string& what) const {
    if (values != n) fail(std::to_string(n) + " positions but " + std::to_string(values) + " " + what);
  }
  void check_scalars(const PointCloud& part) const;
  void check_extra(std::size_t n, std::span<const PlyIntProperty> extra) const;

  fs::path path;
  PointsLayout layout;
  std::unique_ptr<PointsEncoder> encoder;
  OutputFile file;
  std::uint64_t appended = 0;
};

void PointCloudWriter::State::check(const PointCloud& part, std::span<const PlyIntProperty> extra) const {
  const std::size_t n = part.size();
  if (part.origin != layout.origin)
    fail("a part about " + point_text(part.origin) + ", not the cloud's origin " + point_text(layout.origin));
  if (n > layout.count - appended)
    fail("more than the " + std::to_string(layout.count) + " points declared");
  if (layout.normals) check_size(n, part.normals.size(), "normals");
  if (layout.colors) check_size(n, part.colors.size(), "colours");
  check_scalars(part);
  check_extra(n, extra);
}

// The part's first scalars are the layout's, each value in its type.
void PointCloudWriter::State::check_scalars(const PointCloud& part) const {
  if (part.scalars.size() < layout.scalars.size())
    fail("a part with " + std::to_string(part.scalars.size()) + " scalars, not the cloud's " +
         std::to_string(layout.scalars.size()));
  for (std::size_t k = 0; k < layout.scalars.size(); ++k) {
    const ScalarProperty& s = part.scalars[k];
    if (s.name != layout.scalars[k].name || s.type != layout.scalars[k].type)
      fail("a part's scalar " + quote(s.name) + " where the cloud has " + quote(layout.scalars[k].name));
    check_size(part.size(), s.values.size(), "values of " + quote(s.name));
    for (const double v : s.values)
      if (!io::as_type(v, s.type))
        fail("value " + io::text_of(v) + " of " + quote(s.name) + " does not fit its type " +
             std::string(io::name_of(s.type)));
  }
}

void PointCloudWriter::State::check_extra(std::size_t n, std::span<const PlyIntProperty> extra) const {
  if (extra.size() != layout.extra.size())
    fail(std::to_string(extra.size()) + " extra properties for the cloud's " + std::to_string(layout.extra.size()));
  for (std::size_t k = 0; k < extra.size(); ++k) {
    if (extra[k].name != layout.extra[k])
      fail("extra property " + quote(extra[k].name) + " where the cloud has " + quote(layout.extra[k]));
    check_size(n, extra[k].values.size(), "values of " + quote(extra[k].name));
  }
}

PointCloudWriter::PointCloudWriter(const fs::path& path, PointsLayout layout)
    : PointCloudWriter(path, points_format_of(path), std::move(layout)) {}

PointCloudWriter::PointCloudWriter(const fs::path& path, PointsFormat format, PointsLayout layout)
    : state_(std::make_unique<State>(path, format, std::move(layout))) {}

PointCloudWriter::~PointCloudWriter() = default;

void PointCloudWriter::append(const PointCloud& part, std::span<const PlyIntProperty> extra) {
  state_->check(part, extra);
  state_->encoder->write(state_->file.stream(), part, extra);
  state_->appended += part.size();
}

void PointCloudWriter::commit() {
  if (state_->appended != state_->layout.count)
    state_->fail(std::to_string(state_->appended) + " of the " + std::to_string(state_->layout.count) +
                 " points declared");
  state_->file.commit();
}

}  // namespace pss
