// A point cloud file read a part at a time (include/pss/io/point_stream.hpp, issue 28): the
// parts, whatever their size, make up the cloud the whole-file reader gives, and a fault
// late in the file is found when the part that holds it is read.
#include <gtest/gtest.h>

#include <array>
#include <bit>
#include <cstdint>
#include <string>
#include <vector>

#include "pss/core/error.hpp"
#include "pss/io/point_cloud_file.hpp"
#include "pss/io/point_stream.hpp"
#include "support/cli.hpp"
#include "support/file_bytes.hpp"

namespace pss {
namespace {

using PointStreamTest = test::CliTest;

// A binary PLY of n points with normals, colours and a scalar, and a face element after them.
std::string binary_ply(int n) {
  std::string b = "ply\nformat binary_little_endian 1.0\nelement vertex " + std::to_string(n) +
                  "\nproperty double x\nproperty double y\nproperty double z\nproperty float nx\nproperty float ny\n"
                  "property float nz\nproperty uchar red\nproperty uchar green\nproperty uchar blue\n"
                  "property int label\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
  for (int i = 0; i < n; ++i) {
    b += test::bytes_of(1000.5 + i) + test::bytes_of(-2.25 * i) + test::bytes_of(0.125 * i * i);
    b += test::bytes_of(0.0f) + test::bytes_of(float(i % 3)) + test::bytes_of(1.0f);
    b += test::bytes_of(std::uint8_t(i)) + test::bytes_of(std::uint8_t(2 * i)) + test::bytes_of(std::uint8_t(255 - i)) + test::bytes_of(std::int32_t(-i));
  }
  return b + test::bytes_of(std::uint8_t(3)) + test::bytes_of(0) + test::bytes_of(1) + test::bytes_of(2);
}

// The cloud that parts of `size` points make, gathered as the whole-file readers do.
PointCloud gathered(const std::string& file, std::size_t size, std::vector<std::size_t>& sizes) {
  const auto stream = open_point_stream(file);
  PointPart part;
  std::vector<glm::dvec3> world;
  PointCloud cloud;
  for (std::size_t got; (got = stream->read(part, size)) > 0; part.clear()) {
    sizes.push_back(got);
    EXPECT_EQ(part.size(), got);
    world.insert(world.end(), part.world.begin(), part.world.end());
    cloud.normals.insert(cloud.normals.end(), part.normals.begin(), part.normals.end());
    cloud.colors.insert(cloud.colors.end(), part.colors.begin(), part.colors.end());
    if (cloud.scalars.empty()) cloud.scalars = part.scalars;
    else
      for (std::size_t k = 0; k < part.scalars.size(); ++k)
        cloud.scalars[k].values.insert(cloud.scalars[k].values.end(), part.scalars[k].values.begin(),
                                       part.scalars[k].values.end());
  }
  EXPECT_EQ(stream->read(part, size), 0u) << "a finished stream stays finished";
  cloud.mesh_vertices = stream->mesh_vertices();
  set_world_positions(cloud, world);
  tidy_normals(cloud);
  return cloud;
}

void expect_same(const PointCloud& a, const PointCloud& b) {
  ASSERT_EQ(a.size(), b.size());
  EXPECT_EQ(a.origin, b.origin);
  EXPECT_EQ(a.positions, b.positions);
  EXPECT_EQ(a.normals, b.normals);
  EXPECT_EQ(a.colors, b.colors);
  ASSERT_EQ(a.scalars.size(), b.scalars.size());
  for (std::size_t k = 0; k < a.scalars.size(); ++k) {
    EXPECT_EQ(a.scalars[k].name, b.scalars[k].name);
    EXPECT_EQ(a.scalars[k].type, b.scalars[k].type);
    EXPECT_EQ(a.scalars[k].values, b.scalars[k].values);
  }
  EXPECT_EQ(a.mesh_vertices, b.mesh_vertices);
}

TEST_F(PointStreamTest, PartsOfAnySizeMakeUpTheWholeRead) {
  std::string xyz;
  for (int i = 0; i < 10; ++i)
    xyz += std::to_string(596700.25 + i) + " " + std::to_string(-3.5 * i) + " 7 0 " + std::to_string(i) + " 1\n";
  const std::string files[] = {write("a.ply", binary_ply(10)), write("a.xyz", "# comment\n" + xyz),
                               write("a.las", test::las_12_format_2(10, 3))};
  for (const std::string& file : files) {
    const PointCloud whole = read_point_cloud(file);
    ASSERT_EQ(whole.size(), 10u);
    for (const std::size_t size : {1u, 3u, 4u, 10u, 64u}) {
      SCOPED_TRACE(file + ", parts of " + std::to_string(size));
      std::vector<std::size_t> sizes;
      expect_same(gathered(file, size, sizes), whole);
      for (std::size_t k = 0; k + 1 < sizes.size(); ++k) EXPECT_EQ(sizes[k], size) << "only the last part is short";
    }
  }
  EXPECT_EQ(open_point_stream(files[0])->declared_count(), 10u);
  EXPECT_EQ(open_point_stream(files[1])->declared_count(), 0u) << "an XYZ file declares no count";
  EXPECT_TRUE(read_point_cloud(files[0]).mesh_vertices);
}

// A truncated file is refused when the part that reaches its end is read, not before: the
// parts before it are whole.
TEST_F(PointStreamTest, ATruncationLateInTheFileIsFoundWhereItIs) {
  std::string ply = binary_ply(10);
  ply.resize(ply.find("end_header\n") + 11 + 7 * 43 + 20);  // 43 bytes a vertex: 7 and a half
  const std::string file = write("cut.ply", ply);
  const auto stream = open_point_stream(file);
  PointPart part;
  EXPECT_EQ(stream->read(part, 4), 4u);
  const std::string message = test::error_of([&] { stream->read(part, 4); });
  EXPECT_NE(message.find("cut.ply: truncated: expected 10 vertices, read 7"), std::string::npos) << message;
  EXPECT_EQ(test::error_of([&] { open_point_stream(write("bad.xyz", "1 2 3\n4 5\n")); }), "")
      << "opening reads no point";
}

TEST_F(PointStreamTest, OnlyTheFormatsOfLargeCloudsAreStreamed) {
  const std::string message = test::error_of([&] { open_point_stream(write("m.obj", "v 1 2 3\n")); });
  EXPECT_NE(message.find("m.obj: cannot be read a part at a time"), std::string::npos) << message;
  PointPart part;
  const std::string empty = test::error_of([&] { open_point_stream(write("e.xyz", "# nothing\n"))->read(part, 1); });
  EXPECT_NE(empty.find("e.xyz: no points"), std::string::npos) << empty;
}

}  // namespace
}  // namespace pss
