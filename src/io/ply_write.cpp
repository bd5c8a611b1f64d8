// write_ply: binary little-endian, the layout Open3D, PCL and MeshLab read.
#include <algorithm>
#include <array>
#include <bit>
#include <string>
#include <string_view>
#include <vector>

#include "pss/core/error.hpp"
#include "pss/io/output_file.hpp"
#include "pss/io/ply.hpp"
#include "ply_types.hpp"
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
std::vector<std::string> scalar_names(const PointCloud& cloud, std::span<const PlyIntProperty> extra) {
  const auto in_extra = [&](const std::string& name) {
    return std::any_of(extra.begin(), extra.end(), [&](const PlyIntProperty& p) { return p.name == name; });
  };
  const auto in_scalars = [&](const std::string& name) {
    return std::any_of(cloud.scalars.begin(), cloud.scalars.end(),
                       [&](const ScalarProperty& s) { return s.name == name; });
  };
  std::vector<std::string> names;
  for (const ScalarProperty& s : cloud.scalars) {
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

}  // namespace

void write_ply(const fs::path& path, const PointCloud& cloud, std::span<const PlyIntProperty> extra) {
  const std::size_t n = cloud.size();
  if (cloud.has_normals() && cloud.normals.size() != n)
    throw file_error(path, "cannot write: " + std::to_string(n) + " positions but " +
                               std::to_string(cloud.normals.size()) + " normals");
  if (cloud.has_colors() && cloud.colors.size() != n)
    throw file_error(path, "cannot write: " + std::to_string(n) + " positions but " +
                               std::to_string(cloud.colors.size()) + " colours");
  const auto check_size = [&](std::size_t values, const std::string& name) {
    if (values != n)
      throw file_error(path, "cannot write: " + std::to_string(n) + " positions but " + std::to_string(values) +
                                 " values of " + quote(name));
  };
  for (const ScalarProperty& s : cloud.scalars) {
    check_size(s.values.size(), s.name);
    for (const double v : s.values)
      if (!as_type(v, s.type))
        throw file_error(path, "cannot write: value " + text_of(v) + " of " + quote(s.name) +
                                   " does not fit its type " + std::string(name_of(s.type)));
  }
  for (const PlyIntProperty& p : extra) check_size(p.values.size(), p.name);
  const std::vector<std::string> scalars = scalar_names(cloud, extra);
  std::vector<std::string_view> names = {"x", "y", "z"};
  if (cloud.has_normals()) names.insert(names.end(), {"nx", "ny", "nz"});
  if (cloud.has_colors()) names.insert(names.end(), {"red", "green", "blue"});
  names.insert(names.end(), scalars.begin(), scalars.end());
  for (const PlyIntProperty& p : extra) names.push_back(p.name);
  check_names(path, names);

  // A cloud away from the world's origin (cloud.hpp) is written in double, the origin added.
  const bool recentred = cloud.has_origin();
  OutputFile file(path);
  std::ostream& out = file.stream();
  out << "ply\nformat binary_little_endian 1.0\ncomment written by pss\nelement vertex " << n << "\n";
  for (const char* axis : {"x", "y", "z"}) out << "property " << (recentred ? "double " : "float ") << axis << "\n";
  if (cloud.has_normals()) out << "property float nx\nproperty float ny\nproperty float nz\n";
  if (cloud.has_colors()) out << "property uchar red\nproperty uchar green\nproperty uchar blue\n";
  for (std::size_t k = 0; k < scalars.size(); ++k)
    out << "property " << name_of(cloud.scalars[k].type) << " " << scalars[k] << "\n";
  for (const PlyIntProperty& p : extra) out << "property int " << p.name << "\n";
  out << "end_header\n";

  // Records go out in chunks: one write per chunk, without a second copy of a large cloud.
  std::size_t stride =
      (recentred ? 24 : 12) + (cloud.has_normals() ? 12 : 0) + (cloud.has_colors() ? 3 : 0) + 4 * extra.size();
  for (const ScalarProperty& s : cloud.scalars) stride += size_of(s.type);
  constexpr std::size_t kChunk = 1 << 16;
  std::vector<char> buffer(std::min(n, kChunk) * stride);
  for (std::size_t begin = 0; begin < n; begin += kChunk) {
    const std::size_t end = std::min(n, begin + kChunk);
    char* o = buffer.data();
    for (std::size_t i = begin; i < end; ++i) {
      if (recentred) {
        const glm::dvec3 p = cloud.world(i);
        for (int k = 0; k < 3; ++k) o = store_little_endian(o, p[k]);
      } else {
        for (int k = 0; k < 3; ++k) o = store_little_endian(o, cloud.positions[i][k]);
      }
      if (cloud.has_normals())
        for (int k = 0; k < 3; ++k) o = store_little_endian(o, cloud.normals[i][k]);
      if (cloud.has_colors())
        for (int k = 0; k < 3; ++k) o = store_little_endian(o, cloud.colors[i][k]);
      for (const ScalarProperty& s : cloud.scalars) o = store_scalar(o, s.values[i], s.type);
      for (const PlyIntProperty& p : extra) o = store_little_endian(o, p.values[i]);
    }
    out.write(buffer.data(), o - buffer.data());
  }
  file.commit();
}

}  // namespace pss
