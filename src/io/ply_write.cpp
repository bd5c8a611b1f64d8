// The PLY writer (write_ply, PointCloudWriter): binary little-endian, the layout Open3D, PCL
// and MeshLab read.
#include <algorithm>
#include <array>
#include <bit>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "pss/core/error.hpp"
#include "pss/io/ply.hpp"
#include "pss/io/point_cloud_writer.hpp"
#include "ply_types.hpp"
#include "point_encoders.hpp"
#include "text.hpp"

namespace pss {
namespace {

namespace fs = std::filesystem;
using namespace io;  // the PLY scalar types (ply_types.hpp)

template <class T>
char* store_little_endian(char* out, T value) {
  auto raw = std::bit_cast<std::array<char, sizeof(T)>>(value);
  if (std::endian::native != std::endian::little) std::reverse(raw.begin(), raw.end());
  return std::copy(raw.begin(), raw.end(), out);
}

// A scalar's value in its type (as_type has checked that it fits).
char* store_scalar(char* out, double v, Scalar type) {
  switch (type) {
    case Scalar::int8: return store_little_endian(out, std::int8_t(v));
    case Scalar::uint8: return store_little_endian(out, std::uint8_t(v));
    case Scalar::int16: return store_little_endian(out, std::int16_t(v));
    case Scalar::uint16: return store_little_endian(out, std::uint16_t(v));
    case Scalar::int32: return store_little_endian(out, std::int32_t(v));
    case Scalar::uint32: return store_little_endian(out, std::uint32_t(v));
    case Scalar::float32: return store_little_endian(out, float(v));
    case Scalar::float64: return store_little_endian(out, v);
  }
  return out;
}

// The names the scalars are written under. One that an extra property also has (an input's
// own 'status' beside pss project's) becomes input_NAME, prefixed again while taken, so that
// no reader has to choose between two properties of one name.
std::vector<std::string> scalar_names(const PointsLayout& layout) {
  const auto in_extra = [&](const std::string& name) {
    return std::find(layout.extra.begin(), layout.extra.end(), name) != layout.extra.end();
  };
  const auto in_scalars = [&](const std::string& name) {
    return std::any_of(layout.scalars.begin(), layout.scalars.end(),
                       [&](const ScalarProperty& s) { return s.name == name; });
  };
  std::vector<std::string> names;
  for (const ScalarProperty& s : layout.scalars) {
    std::string name = s.name;
    if (in_extra(name)) {
      name = "input_" + name;
      while (in_extra(name) || in_scalars(name)) name = "input_" + name;
    }
    names.push_back(std::move(name));
  }
  return names;
}

// Every property name of the header, once each and without blanks (which would split the
// header line into other words).
void check_names(const fs::path& path, const std::vector<std::string_view>& names) {
  for (auto name = names.begin(); name != names.end(); ++name) {
    if (name->empty() || std::any_of(name->begin(), name->end(), [](unsigned char c) { return c <= ' ' || c >= 127; }))
      throw file_error(path, "cannot write: invalid property name " + quote(*name));
    if (std::find(names.begin(), name, *name) != name)
      throw file_error(path, "cannot write: two properties named " + quote(*name));
  }
}

class PlyEncoder final : public PointsEncoder {
 public:
  PlyEncoder(const fs::path& path, const PointsLayout& layout)
      : layout_(layout), scalar_names_(scalar_names(layout)), recentred_(layout.has_origin()) {
    std::vector<std::string_view> names = {"x", "y", "z"};
    if (layout_.normals) names.insert(names.end(), {"nx", "ny", "nz"});
    if (layout_.colors) names.insert(names.end(), {"red", "green", "blue"});
    names.insert(names.end(), scalar_names_.begin(), scalar_names_.end());
    names.insert(names.end(), layout_.extra.begin(), layout_.extra.end());
    check_names(path, names);
    stride_ = (recentred_ ? 24 : 12) + (layout_.normals ? 12 : 0) + (layout_.colors ? 3 : 0) + 4 * layout_.extra.size();
    for (const ScalarProperty& s : layout_.scalars) stride_ += size_of(s.type);
  }

  void write_header(std::ostream& out) override {
    out << "ply\nformat binary_little_endian 1.0\ncomment written by pss\nelement vertex " << layout_.count << "\n";
    for (const char* axis : {"x", "y", "z"}) out << "property " << (recentred_ ? "double " : "float ") << axis << "\n";
    if (layout_.normals) out << "property float nx\nproperty float ny\nproperty float nz\n";
    if (layout_.colors) out << "property uchar red\nproperty uchar green\nproperty uchar blue\n";
    for (std::size_t k = 0; k < scalar_names_.size(); ++k)
      out << "property " << name_of(layout_.scalars[k].type) << " " << scalar_names_[k] << "\n";
    for (const std::string& name : layout_.extra) out << "property int " << name << "\n";
    out << "end_header\n";
  }

  // Records go out in chunks: one write per chunk, without a second copy of a large part.
  void write(std::ostream& out, const PointCloud& part, std::span<const PlyIntProperty> extra) override {
    const std::size_t n = part.size();
    constexpr std::size_t kChunk = 1 << 16;
    std::vector<char> buffer(std::min(n, kChunk) * stride_);
    for (std::size_t begin = 0; begin < n; begin += kChunk) {
      const std::size_t end = std::min(n, begin + kChunk);
      char* o = buffer.data();
      for (std::size_t i = begin; i < end; ++i) o = store_record(o, part, extra, i);
      out.write(buffer.data(), o - buffer.data());
    }
  }

 private:
  char* store_record(char* o, const PointCloud& part, std::span<const PlyIntProperty> extra, std::size_t i) const {
    if (recentred_) {
      const glm::dvec3 p = part.world(i);
      for (int k = 0; k < 3; ++k) o = store_little_endian(o, p[k]);
    } else {
      for (int k = 0; k < 3; ++k) o = store_little_endian(o, part.positions[i][k]);
    }
    if (layout_.normals)
      for (int k = 0; k < 3; ++k) o = store_little_endian(o, part.normals[i][k]);
    if (layout_.colors)
      for (int k = 0; k < 3; ++k) o = store_little_endian(o, part.colors[i][k]);
    for (std::size_t k = 0; k < layout_.scalars.size(); ++k)
      o = store_scalar(o, part.scalars[k].values[i], layout_.scalars[k].type);
    for (const PlyIntProperty& p : extra) o = store_little_endian(o, p.values[i]);
    return o;
  }

  PointsLayout layout_;
  std::vector<std::string> scalar_names_;
  // A cloud away from the world's origin (cloud.hpp) is written in double, the origin added.
  bool recentred_;
  std::size_t stride_ = 0;  // bytes a record
};

}  // namespace

std::unique_ptr<PointsEncoder> ply_encoder(const fs::path& path, const PointsLayout& layout) {
  return std::make_unique<PlyEncoder>(path, layout);
}

void write_ply(const fs::path& path, const PointCloud& cloud, std::span<const PlyIntProperty> extra) {
  PointCloudWriter writer(path, PointsFormat::ply, layout_of(cloud, extra));
  writer.append(cloud, extra);
  writer.commit();
}

}  // namespace pss
