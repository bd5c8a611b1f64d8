// The point cloud formats beyond PLY and XYZ (OBJ, STL, PCD, LAS), PLY colours, and
// read_point_cloud's choice by extension. Every file is written byte by byte here, and every
// expectation is a value written into it.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "pss/core/error.hpp"
#include "pss/io/ply.hpp"
#include "pss/points/project_cloud.hpp"
#include "support/cli.hpp"

namespace {

using pss::PointCloud;
using pss::Rgb8;
using pss::vec3;
using FormatTest = pss::test::CliTest;

constexpr float kNan = std::numeric_limits<float>::quiet_NaN();

// Little-endian bytes, as STL, PCD (from PCL on any current machine) and LAS store them.
class Bytes {
 public:
  template <class T>
  Bytes& put(T value) {
    auto raw = std::bit_cast<std::array<char, sizeof(T)>>(value);
    if constexpr (std::endian::native == std::endian::big) std::reverse(raw.begin(), raw.end());
    data_.append(raw.data(), raw.size());
    return *this;
  }
  Bytes& text(const std::string& s) {
    data_ += s;
    return *this;
  }
  Bytes& zeros(std::size_t n) { return text(std::string(n, '\0')); }
  const std::string& str() const { return data_; }

 private:
  std::string data_;
};

// A reader must refuse `file` with one line that names it and says `problem`.
template <class Read>
void expect_refused(Read read, const std::string& file, const std::string& problem) {
  const std::string message = pss::test::error_of([&] { read(file); });
  EXPECT_EQ(message.rfind(file + ": ", 0), 0u) << "not a file error: '" << message << "', expected " << problem;
  EXPECT_NE(message.find(problem), std::string::npos) << message;
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
}

// ---------------------------------------------------------------------------------------
// PLY colours

TEST_F(FormatTest, PlyColoursOfAnyType) {
  const PointCloud uchar = pss::read_ply(write("u.ply",
                                               "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\n"
                                               "property float y\nproperty float z\nproperty uchar red\n"
                                               "property uchar green\nproperty uchar blue\nproperty uchar alpha\n"
                                               "end_header\n1 2 3 255 128 0 9\n4 5 6 1 2 3 9\n"));
  EXPECT_EQ(uchar.colors, (std::vector<Rgb8>{{255, 128, 0}, {1, 2, 3}}));
  const PointCloud other = pss::read_ply(write("f.ply",
                                               "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n"
                                               "property float y\nproperty float z\nproperty float diffuse_red\n"
                                               "property ushort diffuse_green\nproperty int diffuse_blue\n"
                                               "end_header\n1 2 3 0.5 65535 300\n"));
  EXPECT_EQ(other.colors, (std::vector<Rgb8>{{128, 255, 255}}));
  const PointCloud partial = pss::read_ply(write("p.ply",
                                                 "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n"
                                                 "property float y\nproperty float z\nproperty uchar red\n"
                                                 "property uchar green\nend_header\n1 2 3 4 5\n"));
  EXPECT_FALSE(partial.has_colors());
  expect_refused(pss::read_ply,
                 write("n.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
                                "property float z\nproperty float red\nproperty float green\nproperty float blue\n"
                                "end_header\n1 2 3 0 nan 0\n"),
                 "vertex 0 has a non-finite colour");
}

TEST_F(FormatTest, PlyWritesColoursAsUchar) {
  PointCloud cloud;
  cloud.positions = {{1, 2, 3}, {4, 5, 6}};
  cloud.normals = {{0, 0, 1}, {1, 0, 0}};
  cloud.colors = {{255, 0, 7}, {1, 2, 3}};
  pss::write_ply(path("c.ply"), cloud);
  EXPECT_NE(read(path("c.ply")).find("property float nz\nproperty uchar red\nproperty uchar green\nproperty uchar blue\n"
                               "end_header\n"),
            std::string::npos);
  const PointCloud back = pss::read_ply(path("c.ply"));
  EXPECT_EQ(back.positions, cloud.positions);
  EXPECT_EQ(back.normals, cloud.normals);
  EXPECT_EQ(back.colors, cloud.colors);
  cloud.colors.pop_back();
  EXPECT_THROW(pss::write_ply(path("d.ply"), cloud), pss::Error);
}

// Projection moves points but keeps their order: the colours stay with them.
TEST_F(FormatTest, ProjectionKeepsColours) {
  PointCloud cloud;
  for (int i = 0; i < 20; ++i)
    for (int j = 0; j < 20; ++j) {
      cloud.positions.emplace_back(0.1f * float(i), 0.1f * float(j), 0.01f * float((i * 7 + j * 3) % 5));
      cloud.colors.emplace_back(i, j, 7);
    }
  pss::Stats stats;
  const pss::CloudProjection out =
      pss::project_cloud(cloud, pss::ProjectionParams::from_h(0.2f), pss::Backend::cpu, stats);
  EXPECT_EQ(out.cloud.colors, cloud.colors);
}

}  // namespace
