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
#include "pss/io/obj.hpp"
#include "pss/io/ply.hpp"
#include "pss/io/stl.hpp"
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
// OBJ

TEST_F(FormatTest, ObjVerticesIgnoreWAndOtherStatements) {
  const PointCloud cloud = pss::read_obj(write("m.obj",
                                               "# a comment\nmtllib m.mtl\no thing\ng part\ns 1\nusemtl red\n"
                                               "v 1 2 3\r\nv -4.5 +5e-1 6 1.0\nvt 0.5 0.5\n\nv 7 8 9 # end\n"
                                               "f 1 2 3\nf 1/1 2/1 3/1\nl 1 2\n"));
  ASSERT_EQ(cloud.size(), 3u);
  EXPECT_EQ(cloud.positions[0], vec3(1, 2, 3));
  EXPECT_EQ(cloud.positions[1], vec3(-4.5f, 0.5f, 6));
  EXPECT_EQ(cloud.positions[2], vec3(7, 8, 9));
  EXPECT_FALSE(cloud.has_normals()) << "no vn at all";
  EXPECT_FALSE(cloud.has_colors());
}

TEST_F(FormatTest, ObjVertexColoursOnlyWhenEveryVertexHasThem) {
  const PointCloud colored = pss::read_obj(write("c.obj", "v 0 0 0 1 0 0.2\nv 1 0 0 0 0.5 1\n"));
  EXPECT_EQ(colored.colors, (std::vector<Rgb8>{{255, 0, 51}, {0, 128, 255}}));
  const PointCloud partly = pss::read_obj(write("p.obj", "v 0 0 0 1 0 0.2\nv 1 0 0\nv 2 0 0 1 1 1\n"));
  EXPECT_EQ(partly.size(), 3u);
  EXPECT_FALSE(partly.has_colors());
}

TEST_F(FormatTest, ObjFaceNormalsFirstWinsAndUnnamedVerticesGetZero) {
  const PointCloud cloud = pss::read_obj(write("n.obj",
                                               "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 5 5 5\n"
                                               "vn 0 0 2\nvn 0 1 0\nvn 1 0 0\n"
                                               "f 1//1 2//1 3//2\n"
                                               "f 3/1/3 2/1/2 -4/1/-1\n"  // v/vt/vn, negative: vertex 1, vn 3
                                               "f 2 3 1\n"));            // no normals: ignored
  ASSERT_EQ(cloud.normals.size(), 4u);
  EXPECT_EQ(cloud.normals[0], vec3(0, 0, 1)) << "normalised, and the first face's";
  EXPECT_EQ(cloud.normals[1], vec3(0, 0, 1));
  EXPECT_EQ(cloud.normals[2], vec3(0, 1, 0)) << "first face wins";
  EXPECT_EQ(cloud.normals[3], vec3(0, 0, 0)) << "named by no face";
}

TEST_F(FormatTest, ObjNormalsPairByOrderOnlyWithoutFaceNormalsAndEqualCounts) {
  const PointCloud paired = pss::read_obj(write("a.obj", "v 0 0 0\nvn 0 0 1\nv 1 0 0\nvn 0 3 0\nf 1 2 1\n"));
  EXPECT_EQ(paired.normals, (std::vector<vec3>{{0, 0, 1}, {0, 1, 0}}));
  const PointCloud fewer = pss::read_obj(write("b.obj", "v 0 0 0\nv 1 0 0\nvn 0 0 1\n"));
  EXPECT_FALSE(fewer.has_normals());
}

TEST_F(FormatTest, ObjErrors) {
  const std::pair<std::string, std::string> cases[] = {
      {"v 1 2 3\nv 4 5 \\\n6\n", "line 2: line continuations ('\\') are not supported"},
      {"v 1 2\n", "line 1: expected 'v x y z [w]' or 'v x y z r g b', found 2 numbers"},
      {"v 1 x 3\n", "line 1: malformed number 'x'"},
      {"v 1 2 3\nv 1 nan 3\n", "line 2: non-finite coordinate"},
      {"v 1 2 3 1 inf 0\n", "line 1: non-finite colour"},
      {"vn 1 2\n", "line 1: expected 'vn x y z', found 2 numbers"},
      {"v 1 2 3\nvn 0 0 1\nf 1//2 1//1 1//1\n", "line 3: face corner '1//2' names a normal not defined before it"},
      {"v 1 2 3\nvn 0 0 1\nf 0//1 1//1 1//1\n", "line 3: face corner '0//1' names a vertex not defined before it"},
      {"v 1 2 3\nvn 0 0 1\nf -2//1 1//1 1//1\n", "line 3: face corner '-2//1' names a vertex not defined before it"},
      {"vn 0 0 1\nf 2//1 1//1 1//1\nv 1 2 3\nv 1 2 3\n", "line 2: face corner '2//1' names a vertex"},
      {"# nothing\ng empty\n", "no vertices"},
  };
  for (const auto& [text, problem] : cases) expect_refused(pss::read_obj, write("bad.obj", text), problem);
}

// ---------------------------------------------------------------------------------------
// STL

// A unit square in the z = 0 plane as two facets; (0,0,0) is written as -0 in the second.
const vec3 kSquare[2][3] = {{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}}, {{-0.0f, 0, 0}, {1, 1, 0}, {0, 1, 0}}};

std::string binary_stl(std::uint32_t declared_facets) {
  Bytes b;
  b.text("solid looks like ASCII but is not").zeros(80 - 33).put(declared_facets);
  for (const auto& facet : kSquare) {
    b.put(0.0f).put(0.0f).put(1.0f);  // the facet normal
    for (const vec3& v : facet) b.put(v.x).put(v.y).put(v.z);
    b.put(std::uint16_t(0));
  }
  return b.str();
}

const std::vector<vec3> kSquareVertices = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};

TEST_F(FormatTest, StlBinaryVerticesOnceInFirstSeenOrderWithoutNormals) {
  const PointCloud cloud = pss::read_stl(write("b.stl", binary_stl(2)));
  EXPECT_EQ(cloud.positions, kSquareVertices);
  EXPECT_FALSE(std::signbit(cloud.positions[0].x)) << "-0 and +0 are one position";
  EXPECT_FALSE(cloud.has_normals()) << "facet normals are not vertex normals";
}

TEST_F(FormatTest, StlAscii) {
  const std::string facets =
      "  facet normal 0 0 1\n    outer loop\n      vertex 0 0 0\n      vertex 1 0 0\n      vertex 1 1 0\n"
      "    endloop\n  endfacet\n"
      "  facet normal 0 0 1\r\n    outer loop\r\n      vertex -0 0 0\r\n      vertex 1 1 0\r\n"
      "      vertex 0 1e0 0\r\n    endloop\r\n  endfacet\r\n";
  const PointCloud cloud = pss::read_stl(write("a.stl", "solid square\n" + facets + "endsolid square\n"));
  EXPECT_EQ(cloud.positions, kSquareVertices);
  EXPECT_FALSE(cloud.has_normals());
  // Two solids one after the other (some tools concatenate them); the name is optional.
  const PointCloud two = pss::read_stl(write("two.stl", "solid\n" + facets + "endsolid\nsolid b\n"
                                                        "facet normal 0 0 1\nouter loop\nvertex 5 5 5\n"
                                                        "vertex 6 5 5\nvertex 5 6 5\nendloop\nendfacet\n"
                                                        "endsolid b\n"));
  EXPECT_EQ(two.size(), 7u);
  EXPECT_EQ(two.positions.back(), vec3(5, 6, 5));
}

TEST_F(FormatTest, StlErrors) {
  const std::string binary = binary_stl(2);
  const std::string facet = "facet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n";
  const std::pair<std::string, std::string> cases[] = {
      {binary.substr(0, binary.size() - 10),
       "not an STL file, or a truncated binary one: 174 bytes, but 84 + 50 x 2 facets = 184"},
      {binary_stl(3), "not an STL file, or a truncated binary one: 184 bytes, but 84 + 50 x 3 facets = 234"},
      {binary_stl(0xFFFFFFFF), "84 + 50 x 4294967295 facets = 214748364834"},
      {binary_stl(0).substr(0, 84), "no facets"},
      {"", "not an STL file (too short for binary, no 'solid' for ASCII)"},
      {"solid x\n" + facet + "endloop\nendfacet\nendsolid\n", "line 6: a facet has 2 vertices, not 3"},
      {"solid x\n" + facet + "vertex 1 1 0\nendloop\nendfacet\n", "truncated: the file ends inside a solid"},
      {"solid x\nvertex 1 1 0\nendsolid\n", "line 2: unexpected 'vertex'"},
      {"solid x\n" + facet + "vertex 1 nan 0\nendloop\nendfacet\nendsolid\n", "line 6: non-finite coordinate"},
      {"solid x\n" + facet + "vertex 1 1\n", "line 6: expected 'vertex x y z'"},
      {"solid x\nfacet normal 0 0 1\nfacet normal 0 0 1\n", "line 3: unexpected 'facet'"},
      {"solid x\nendsolid x\n", "no facets"},
  };
  for (const auto& [bytes, problem] : cases) expect_refused(pss::read_stl, write("bad.stl", bytes), problem);
  // A binary facet with a NaN: the size matches, so it is read as binary and refused.
  std::string nan_facet = binary;
  const float nan = kNan;
  std::memcpy(nan_facet.data() + 84 + 50 + 12 + 4, &nan, 4);
  expect_refused(pss::read_stl, write("nan.stl", nan_facet), "facet 1 has a non-finite coordinate");
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
