#include "fuzz_input.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <system_error>

#include "support/gzip.hpp"

namespace pss::fuzz {

namespace {

namespace fs = std::filesystem;

class Folder {
 public:
  Folder() {
    std::string pattern = (fs::temp_directory_path() / "pss-fuzz-XXXXXX").string();
    if (!::mkdtemp(pattern.data())) finding("cannot make a folder under " + fs::temp_directory_path().string());
    path_ = pattern;
  }
  ~Folder() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

const fs::path& folder() {
  static const Folder f;
  return f.path();
}

}  // namespace

const std::filesystem::path& fresh_folder() {
  const fs::path& dir = folder();
  for (const auto& entry : fs::directory_iterator(dir)) fs::remove_all(entry.path());
  return dir;
}

std::filesystem::path write_file(const std::string& name, std::string_view bytes) {
  const fs::path path = folder() / name;
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), std::streamsize(bytes.size()));
  if (!out.flush()) finding("cannot write " + path.string());
  return path;
}

Parts split_parts(std::string_view input) {
  const std::size_t at = input.find(kSeparator);
  if (at == std::string_view::npos) return {input, {}, false};
  return {input.substr(0, at), input.substr(at + kSeparator.size()), true};
}

Mode take_mode(std::string_view input) {
  if (input.empty()) return {};
  return {static_cast<unsigned char>(input[0]), input.substr(1)};
}

std::filesystem::path write_header_and_data(std::string_view input, const std::string& attached_name,
                                            const std::string& detached_name) {
  const Mode mode = take_mode(input);
  const Parts parts = split_parts(mode.rest);
  const std::string tail = mode.bits & 2 ? gzip(parts.tail) : std::string(parts.tail);
  fresh_folder();
  if (!(mode.bits & 1)) return write_file(attached_name, std::string(parts.head) + tail);
  if (parts.has_tail) write_file("data.raw", tail);
  return write_file(detached_name, parts.head);
}

std::string gzip(std::string_view bytes) { return test::gzip(std::string(bytes)); }

void finding(const std::string& what) {
  std::fprintf(stderr, "pss fuzz finding: %s\n", what.c_str());
  std::abort();
}

void check_cloud(const PointCloud& cloud) {
  if (cloud.positions.empty()) finding("a cloud without points was returned");
  for (const vec3& p : cloud.positions)
    if (!is_finite(p)) finding("a non-finite position was returned");
  if (!cloud.normals.empty() && cloud.normals.size() != cloud.positions.size())
    finding("normals and positions differ in number");
  if (!cloud.colors.empty() && cloud.colors.size() != cloud.positions.size())
    finding("colours and positions differ in number");
  for (const ScalarProperty& s : cloud.scalars) {
    if (s.values.size() != cloud.positions.size()) finding("a scalar property and positions differ in number");
    const auto same_name = [&](const ScalarProperty& t) { return t.name == s.name; };
    if (std::count_if(cloud.scalars.begin(), cloud.scalars.end(), same_name) != 1)
      finding("two scalar properties share a name");
  }
  for (const vec3& n : cloud.normals) {
    const double len = std::sqrt(double(n.x) * n.x + double(n.y) * n.y + double(n.z) * n.z);
    if (!(len == 0 || std::abs(len - 1) < 1e-5)) finding("a normal is neither unit nor zero");
  }
}

void check_volume(const Volume& v) {
  if (!(v.dims.x > 0 && v.dims.y > 0 && v.dims.z > 0)) finding("a volume with non-positive dims was returned");
  if (v.values.size() != std::size_t(v.dims.x) * std::size_t(v.dims.y) * std::size_t(v.dims.z))
    finding("a volume's value count differs from its dims");
  for (const float x : v.values)
    if (!std::isfinite(x)) finding("a non-finite voxel was returned");
  for (int a = 0; a < 3; ++a) {
    if (!(std::isfinite(v.spacing[a]) && v.spacing[a] > 0)) finding("a volume's spacing is not positive and finite");
    if (!std::isfinite(v.origin[a])) finding("a volume's origin is not finite");
  }
}

void report(std::string_view outcome) {
  static const bool verbose = std::getenv("PSS_FUZZ_VERBOSE") != nullptr;
  if (verbose) std::fprintf(stderr, "  %.*s\n", int(outcome.size()), outcome.data());
}

void check_message(std::string_view message) {
  if (message.size() > kMaxMessageBytes)
    finding("an error message of " + std::to_string(message.size()) + " bytes: " + std::string(message.substr(0, 200)));
  for (const char c : message)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f)
      finding("an error message with a control byte: " + one_line(message));
}

}  // namespace pss::fuzz
