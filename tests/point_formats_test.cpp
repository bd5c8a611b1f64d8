// The point cloud formats beyond PLY and XYZ (OBJ, STL, PCD, LAS), PLY colours and scalar
// properties, and read_point_cloud's choice by extension. Every file is written byte by byte
// here, and every expectation is a value written into it.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "pss/core/error.hpp"
#include "pss/io/las.hpp"
#include "pss/io/obj.hpp"
#include "pss/io/off.hpp"
#include "pss/io/pcd.hpp"
#include "pss/io/ply.hpp"
#include "pss/io/point_cloud_file.hpp"
#include "pss/io/point_stream.hpp"
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
// OFF

TEST_F(FormatTest, OffVerticesWithCommentsAndFacesIgnored) {
  const PointCloud cloud = pss::read_off(write("m.off",
                                               "OFF  # a tetrahedron\n"
                                               "\n"
                                               "4 4 6\n"
                                               "0 0 0\n1 0 0 # comment\n0 1 0\n0 0 1.5\n"
                                               "3 0 1 2\n3 0 1 3\n3 0 2 3\n3 1 2 3\n"));
  EXPECT_EQ(cloud.positions, (std::vector<vec3>{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1.5f}}));
  EXPECT_FALSE(cloud.has_normals());
  EXPECT_FALSE(cloud.has_colors());
}

TEST_F(FormatTest, OffCountsOnTheKeywordLineOrWithoutKeyword) {
  for (const std::string text : {"OFF 2 0 0\n1 2 3\n4 5 6\n", "2 0\n1 2 3\n4 5 6\n"}) {
    const PointCloud cloud = pss::read_off(write("m.off", text));
    EXPECT_EQ(cloud.positions, (std::vector<vec3>{{1, 2, 3}, {4, 5, 6}})) << text;
  }
}

TEST_F(FormatTest, OffNormalsAndColoursAsTheKeywordSays) {
  const PointCloud n = pss::read_off(write("n.off", "NOFF\n2 0 0\n0 0 0 0 0 2\n1 0 0 0 1 0\n"));
  EXPECT_EQ(n.normals, (std::vector<vec3>{{0, 0, 1}, {0, 1, 0}}));  // made unit
  EXPECT_FALSE(n.has_colors());
  // Colours: integers are 0..255, numbers with a point 0..1; an alpha may follow.
  const PointCloud c = pss::read_off(write("c.off", "COFF\n3 0 0\n0 0 0 255 0 51\n1 0 0 0.2 1.0 0 1\n2 0 0 1e0 1 2E-1\n"));
  EXPECT_EQ(c.colors, (std::vector<Rgb8>{{255, 0, 51}, {51, 255, 0}, {255, 1, 51}}));
  EXPECT_FALSE(c.has_normals());
  const PointCloud both = pss::read_off(write("cn.off", "STCNOFF\n1 0 0\n1 2 3 1 0 0 10 20 30 0.5 0.5\n"));
  EXPECT_EQ(both.positions, std::vector<vec3>{vec3(1, 2, 3)});
  EXPECT_EQ(both.normals, std::vector<vec3>{vec3(1, 0, 0)});
  EXPECT_EQ(both.colors, std::vector<Rgb8>{Rgb8(10, 20, 30)});
}

// The shared meshes and CGAL's points with normals (shared/data/clouds, beside the checkout),
// read whole: every vertex, and the .pwn file's normals.
TEST_F(FormatTest, SharedOffMeshesAndPointsWithNormals) {
  const std::filesystem::path clouds = std::filesystem::path(PSS_SOURCE_DIR) / "../shared/data/clouds";
  if (!std::filesystem::exists(clouds / "blade.off")) GTEST_SKIP() << "no " << clouds;
  EXPECT_EQ(pss::read_point_cloud(clouds / "blade.off").size(), 8231u);
  EXPECT_EQ(pss::read_point_cloud(clouds / "cylinder_locally_refined.off").size(), 8285u);
  const PointCloud cube = pss::read_point_cloud(clouds / "cube.pwn");
  EXPECT_EQ(cube.size(), 50000u);
  ASSERT_TRUE(cube.has_normals());
  EXPECT_EQ(cube.normals[0], vec3(0, 1, 0));  // its first line: -0.175308 0.371795 0.209773 0 1 0
}

TEST_F(FormatTest, OffErrors) {
  const std::pair<std::string, std::string> cases[] = {
      {"", "empty OFF file"},
      {"# only a comment\n", "empty OFF file"},
      {"PLY\n1 0 0\n", "line 1: expected the keyword OFF (or COFF, NOFF, CNOFF, STOFF, ...), found 'PLY'"},
      {"4OFF\n1 0 0\n1 2 3 4\n", "line 1: '4OFF': only 3-dimensional OFF files are read"},
      {"nOFF\n3\n1 0 0\n1 2 3\n", "line 1: 'nOFF': only 3-dimensional OFF files are read"},
      {"OFF\n", "no vertex count after 'OFF'"},
      {"OFF\n3\n", "line 2: expected the counts 'vertices faces [edges]'"},
      {"OFF\n-1 0 0\n", "line 2: malformed count '-1'"},
      {"OFF\n1.5 0 0\n", "line 2: malformed count '1.5'"},
      {"OFF\n1e30 0 0\n", "line 2: malformed count '1e30'"},
      {"OFF\ninf 0 0\n", "line 2: malformed count 'inf'"},
      {"OFF\n0 0 0\n", "line 2: no vertices"},
      {"OFF\n3 0 0\n1 2 3\n4 5 6\n", "the header says 3 vertices, the file has 2"},
      {"OFF\n1000000000000 0 0\n1 2 3\n", "the header says 1000000000000 vertices, the file has 1"},
      {"OFF\n1 0 0\n1 2\n", "line 3: expected 3 numbers per vertex, found 2"},
      {"NOFF\n1 0 0\n1 2 3\n", "line 3: expected 6 numbers per vertex, found 3"},
      {"COFF\n1 0 0\n1 2 3 4 5\n", "line 3: expected 3 + 3 or 4 numbers per vertex, found 5"},
      {"OFF\n1 0 0\n1 x 3\n", "line 3: malformed number 'x'"},
      {"OFF\n1 0 0\n1 inf 3\n", "line 3: non-finite coordinate"},
      {"COFF\n1 0 0\n1 2 3 nan 0 0\n", "line 3: non-finite colour"},
  };
  for (const auto& [text, problem] : cases) expect_refused(pss::read_off, write("bad.off", text), problem);
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

// A file that declares faces holds a mesh's vertices, whose surface ends at them (`pss render
// --borders auto` clips it, points/borders.hpp); points alone are a scan's.
TEST_F(FormatTest, MeshFilesSayTheirPointsAreVertices) {
  const std::string tri = "0 0 0\n1 0 0\n0 1 0\n";
  EXPECT_TRUE(pss::read_off(write("f.off", "OFF\n3 1 0\n" + tri + "3 0 1 2\n")).mesh_vertices);
  EXPECT_FALSE(pss::read_off(write("p.off", "OFF\n3 0 0\n" + tri)).mesh_vertices);
  EXPECT_TRUE(pss::read_obj(write("f.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")).mesh_vertices);
  EXPECT_FALSE(pss::read_obj(write("p.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n")).mesh_vertices);
  EXPECT_TRUE(pss::read_stl(write("f.stl", binary_stl(2))).mesh_vertices);
  const std::string ply = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                          "property float z\n";
  EXPECT_TRUE(pss::read_ply(write("f.ply", ply + "element face 1\nproperty list uchar int vertex_indices\nend_header\n" +
                                               tri + "3 0 1 2\n"))
                  .mesh_vertices);
  EXPECT_FALSE(pss::read_ply(write("z.ply", ply + "element face 0\nproperty list uchar int vertex_indices\nend_header\n" +
                                                tri))
                   .mesh_vertices);
  EXPECT_FALSE(pss::read_ply(write("p.ply", ply + "end_header\n" + tri)).mesh_vertices);
  EXPECT_FALSE(pss::read_point_cloud(write("p.xyz", tri)).mesh_vertices);
}

// ---------------------------------------------------------------------------------------
// PCD

TEST_F(FormatTest, PcdAsciiWithNormalsColoursSkippedFieldsAndNaNPoints) {
  // rgb is TYPE F: PCL writes the packed bits as an integer (newer) or as the float (older).
  const float packed = std::bit_cast<float>(std::uint32_t(0x00102030));
  char old_style[64];
  std::snprintf(old_style, sizeof old_style, "%.9g", double(packed));
  const std::string file = "# .PCD v0.7 - Point Cloud Data file format\nVERSION 0.7\n"
                           "FIELDS x y z hist normal_x normal_y normal_z rgb\n"
                           "SIZE 4 4 4 4 4 4 4 4\nTYPE F F F F F F F F\nCOUNT 1 1 1 3 1 1 1 1\n"
                           "WIDTH 2\nHEIGHT 2\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS 4\nDATA ascii\n"
                           "1 2 3 9 9 9 0 0 2 16744512\n"
                           "nan nan nan 9 9 9 nan nan nan 0\n"
                           "-1.5 +2 1e1 0 0 0 0 1 0 " + std::string(old_style) + "\n"
                           "4 5 6 0 0 0 3 0 4 4278190335\n";  // rgba-style alpha in the top byte
  const PointCloud cloud = pss::read_pcd(write("a.pcd", file));
  EXPECT_EQ(cloud.positions, (std::vector<vec3>{{1, 2, 3}, {-1.5f, 2, 10}, {4, 5, 6}}));
  ASSERT_EQ(cloud.normals.size(), 3u) << "the NaN normal left with its point";
  EXPECT_EQ(cloud.normals[0], vec3(0, 0, 1));
  EXPECT_EQ(cloud.normals[1], vec3(0, 1, 0));
  EXPECT_NEAR(cloud.normals[2].x, 0.6f, 1e-7f);
  EXPECT_EQ(cloud.colors, (std::vector<Rgb8>{{0xFF, 0x80, 0x40}, {0x10, 0x20, 0x30}, {0, 0, 0xFF}}));
}

TEST_F(FormatTest, PcdBinaryAnyTypeAndSize) {
  // x F8, y I2, z U1, a skipped I4 field of COUNT 2, rgba U4, normals F4, then a U8.
  const std::string header = "VERSION .7\nFIELDS x y z label rgba normal_x normal_y normal_z t\n"
                             "SIZE 8 2 1 4 4 4 4 4 8\nTYPE F I U I U F F F U\nCOUNT 1 1 1 2 1 1 1 1 1\n"
                             "WIDTH 3\nHEIGHT 1\nPOINTS 3\nDATA binary\n";
  Bytes b;
  b.put(0.125).put(std::int16_t(-300)).put(std::uint8_t(250)).put(7).put(8).put(std::uint32_t(0xFF0A0B0C));
  b.put(1.0f).put(0.0f).put(0.0f).put(std::uint64_t(1) << 40);
  b.put(double(kNan)).put(std::int16_t(0)).put(std::uint8_t(0)).put(0).put(0).put(std::uint32_t(0x00FFFFFF));
  b.put(kNan).put(kNan).put(kNan).put(std::uint64_t(0));
  b.put(-2.0).put(std::int16_t(32767)).put(std::uint8_t(0)).put(0).put(0).put(std::uint32_t(0x00000102));
  b.put(0.0f).put(-5.0f).put(0.0f).put(std::uint64_t(0));
  const PointCloud cloud = pss::read_pcd(write("b.pcd", header + b.str()));
  EXPECT_EQ(cloud.positions, (std::vector<vec3>{{0.125f, -300, 250}, {-2, 32767, 0}}));
  EXPECT_EQ(cloud.normals, (std::vector<vec3>{{1, 0, 0}, {0, -1, 0}}));
  EXPECT_EQ(cloud.colors, (std::vector<Rgb8>{{0x0A, 0x0B, 0x0C}, {0, 1, 2}}));
}

// 4 points x y z (F4) and rgb (U4), stored field after field: x 1 1 1 1, y 0 0 0 2, z -1 -1
// NaN -1, rgb FF8040 010203 000000 FF8040, compressed by hand into literal runs and short and
// long back-references, overlapping ones included.
std::string compressed_pcd_data() {
  Bytes lzf;
  lzf.put(std::uint8_t(3)).put(1.0f);                                            // literal x0
  lzf.put(std::uint8_t(0xE0)).put(std::uint8_t(3)).put(std::uint8_t(3));        // 12 bytes from 4 back
  lzf.put(std::uint8_t(0)).put(std::uint8_t(0));                                 // literal 0x00
  lzf.put(std::uint8_t(0xE0)).put(std::uint8_t(2)).put(std::uint8_t(0));        // 11 bytes from 1 back
  lzf.put(std::uint8_t(3)).put(2.0f);                                            // literal y3
  lzf.put(std::uint8_t(3)).put(-1.0f);                                           // literal z0
  lzf.put(std::uint8_t(0x40)).put(std::uint8_t(3));                              // 4 bytes from 4 back
  lzf.put(std::uint8_t(7)).put(kNan).put(-1.0f);                                 // literal z2 z3
  lzf.put(std::uint8_t(11)).put(std::uint32_t(0xFF8040)).put(std::uint32_t(0x010203)).put(std::uint32_t(0));
  lzf.put(std::uint8_t(0x40)).put(std::uint8_t(11));                             // 4 bytes from 12 back
  return lzf.str();
}

const std::string kCompressedHeader = "FIELDS x y z rgb\nSIZE 4 4 4 4\nTYPE F F F U\nCOUNT 1 1 1 1\n"
                                      "WIDTH 4\nHEIGHT 1\nPOINTS 4\nDATA binary_compressed\n";

std::string compressed_pcd(std::uint32_t compressed, std::uint32_t uncompressed, const std::string& lzf) {
  return kCompressedHeader + Bytes().put(compressed).put(uncompressed).str() + lzf;
}

TEST_F(FormatTest, PcdBinaryCompressedWithBackReferences) {
  const std::string lzf = compressed_pcd_data();
  const PointCloud cloud = pss::read_pcd(write("c.pcd", compressed_pcd(std::uint32_t(lzf.size()), 64, lzf)));
  EXPECT_EQ(cloud.positions, (std::vector<vec3>{{1, 0, -1}, {1, 0, -1}, {1, 2, -1}}));
  EXPECT_EQ(cloud.colors, (std::vector<Rgb8>{{0xFF, 0x80, 0x40}, {1, 2, 3}, {0xFF, 0x80, 0x40}}));
  EXPECT_FALSE(cloud.has_normals());
}

TEST_F(FormatTest, PcdErrors) {
  const std::string xyz = "FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\n";
  const std::string two_points = xyz + "WIDTH 2\nHEIGHT 1\nPOINTS 2\n";
  const std::string lzf = compressed_pcd_data();
  const auto size = std::uint32_t(lzf.size());
  const std::pair<std::string, std::string> cases[] = {
      {"", "not a PCD file (no DATA line)"},
      {"ply\nformat ascii 1.0\n", "line 1: unexpected header line 'ply'"},
      {two_points + "DATA zip\n", "unknown DATA 'DATA zip'"},
      {"FIELDS x y\nSIZE 4 4\nTYPE F F\nPOINTS 1\nDATA ascii\n1 2\n", "no field 'z'"},
      {"FIELDS x y z\nSIZE 4 4\nTYPE F F F\nPOINTS 1\nDATA ascii\n1 2 3\n", "SIZE has 2 values for 3 FIELDS"},
      {"FIELDS x y z\nSIZE 4 4 2\nTYPE F F F\nPOINTS 1\nDATA ascii\n1 2 3\n",
       "field 'z' has an unknown TYPE 'F' with SIZE '2'"},
      {"FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 0\nPOINTS 1\nDATA ascii\n1 2 3\n",
       "field 'z' has an invalid COUNT '0'"},
      {"FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 2 1\nPOINTS 1\nDATA ascii\n1 2 2 3\n",
       "field 'y' has COUNT 2, not 1"},
      {xyz + "WIDTH 2\nHEIGHT 2\nPOINTS 3\nDATA ascii\n", "WIDTH x HEIGHT = 2 x 2 is not POINTS 3"},
      {xyz + "WIDTH 4294967296\nHEIGHT 4294967296\nDATA ascii\n", "WIDTH x HEIGHT overflows"},
      {xyz + "POINTS 0\nDATA ascii\n", "no points"},
      {xyz + "DATA ascii\n", "header has neither POINTS nor WIDTH and HEIGHT"},
      {two_points + "DATA ascii\n1 2 3\n", "truncated: expected 2 points, read 1"},
      {two_points + "DATA ascii\n1 2 3\n4 5 6\n7 8 9\n", "line 11: more points than the header's 2"},
      {two_points + "DATA ascii\n1 2 3\n4 5\n", "line 10: expected 3 values, found 2"},
      {two_points + "DATA ascii\n1 2 3\n4 five 6\n", "line 10: malformed number 'five'"},
      {two_points + "DATA ascii\nnan 2 3\n4 nan 6\n", "no points: all 2 have a NaN coordinate"},
      {two_points + "DATA ascii\n1 2 3\n4 inf 6\n", "point 1 has an infinite coordinate"},
      {two_points + "DATA binary\n" + std::string(23, '\0'),
       "truncated: 2 points of 12 bytes need more than the 23 bytes after the header"},
      // A count no file could hold: refused before anything is allocated for it.
      {xyz + "POINTS 4000000000000\nDATA binary\n" + std::string(24, '\0'),
       "truncated: 4000000000000 points of 12 bytes need more than the 24 bytes"},
      {kCompressedHeader + "\x01\x00", "truncated: no compressed sizes after the header"},
      {compressed_pcd(size + 1, 64, lzf), "truncated: " + std::to_string(size + 1) + " compressed bytes declared"},
      {compressed_pcd(size, 68, lzf), "the uncompressed size 68 is not that of 4 points of 16 bytes"},
      {compressed_pcd(size - 2, 64, lzf), "corrupt compressed data: the data decompresses to fewer bytes"},
      {compressed_pcd(size + 2, 64, lzf + std::string(2, '\0')),
       "corrupt compressed data: the data decompresses to more bytes than the header says"},
      {compressed_pcd(size - 1, 64, lzf.substr(0, size - 1)),
       "corrupt compressed data: a back-reference passes the end of the compressed data"},
      {compressed_pcd(3, 64, lzf), "corrupt compressed data: a literal run passes the end of the compressed data"},
      {compressed_pcd(size, 64, "\x60\x05" + lzf.substr(2)),
       "corrupt compressed data: a back-reference points before the start of the data"},
      {compressed_pcd(0, 64, lzf), "0 compressed bytes cannot make 64 (LZF expands at most 88 times)"},
      {xyz + "POINTS 357913941\nDATA binary_compressed\n" + Bytes().put(10u).put(4294967292u).str() + "0123456789",
       "10 compressed bytes cannot make 4294967292"},
  };
  for (const auto& [bytes, problem] : cases) expect_refused(pss::read_pcd, write("bad.pcd", bytes), problem);
}

// ---------------------------------------------------------------------------------------
// LAS

struct LasHeader {
  int minor = 2;
  std::uint8_t format = 2;
  std::uint16_t record_length = 26;
  std::uint32_t legacy_points = 0;
  std::uint64_t points = 0;  // 1.4's 64-bit count
  std::uint32_t data_offset = 0;  // 0: right after the header
  std::array<double, 3> scale{0.01, 0.01, 0.01}, offset{};
};

// The public header of LAS 1.minor, field by field (the ASPRS specification's table 3).
std::string las_header(const LasHeader& h) {
  const std::uint16_t size = h.minor >= 4 ? 375 : h.minor == 3 ? 235 : 227;
  Bytes b;
  b.text("LASF").put(std::uint16_t(0)).put(std::uint16_t(0)).zeros(16);  // source id, encoding, GUID
  b.put(std::uint8_t(1)).put(std::uint8_t(h.minor)).zeros(64);            // version, system, software
  b.put(std::uint16_t(1)).put(std::uint16_t(2024)).put(size);
  b.put(h.data_offset ? h.data_offset : std::uint32_t(size)).put(std::uint32_t(0));  // offset, VLRs
  b.put(h.format).put(h.record_length).put(h.legacy_points).zeros(20);
  for (double s : h.scale) b.put(s);
  for (double o : h.offset) b.put(o);
  b.zeros(48);  // max and min x y z
  if (h.minor >= 3) b.zeros(8);  // waveform data
  if (h.minor >= 4) b.zeros(12).put(h.points).zeros(120);  // EVLRs, 64-bit count, by return
  return b.str();
}

// A LAS 1.2 format 2 record: X Y Z, intensity, flags, class (6, building, under the flag
// bits 5-7: synthetic and withheld), angle, user, source, RGB.
std::string las_record_2(std::int32_t x, std::int32_t y, std::int32_t z, std::array<std::uint16_t, 3> rgb) {
  Bytes b;
  b.put(x).put(y).put(z).put(std::uint16_t(100)).put(std::uint8_t(0)).put(std::uint8_t(0b1010'0110)).zeros(2);
  b.put(std::uint16_t(7));
  for (std::uint16_t c : rgb) b.put(c);
  return b.str();
}

TEST_F(FormatTest, Las12Format2ScaleOffsetAndEightBitColours) {
  LasHeader h;
  h.legacy_points = 2;
  h.data_offset = 227 + 54;  // a VLR's worth of bytes between the header and the points
  h.scale = {0.01, 0.5, 0.25};
  h.offset = {100, -200, 1000};
  const std::string file = las_header(h) + std::string(54, 'v') + las_record_2(1000, -3, 8, {255, 128, 0}) +
                           las_record_2(-50, 4, 0, {1, 2, 3});
  const PointCloud cloud = pss::read_las(write("a.las", file));
  ASSERT_EQ(cloud.size(), 2u);
  EXPECT_EQ(cloud.world(0), glm::dvec3(110, -201.5, 1002));
  EXPECT_EQ(cloud.world(1), glm::dvec3(99.5, -198, 1000));
  EXPECT_EQ(cloud.colors, (std::vector<Rgb8>{{255, 128, 0}, {1, 2, 3}})) << "8-bit values stored as 16-bit";
  EXPECT_FALSE(cloud.has_normals());
  ASSERT_EQ(cloud.scalars.size(), 2u);
  EXPECT_EQ(cloud.scalars[0].name, "intensity");
  EXPECT_EQ(cloud.scalars[0].type, pss::ScalarType::uint16);
  EXPECT_EQ(cloud.scalars[0].values, (std::vector<double>{100, 100}));
  EXPECT_EQ(cloud.scalars[1].name, "classification");
  EXPECT_EQ(cloud.scalars[1].type, pss::ScalarType::uint8);
  EXPECT_EQ(cloud.scalars[1].values, (std::vector<double>{6, 6})) << "the class without its flag bits";
}

// Airborne scans are stored in millimetres about a projected (UTM) offset: the positions keep
// them, where floats at 4·10⁶ m would round to quarter metres (cloud.hpp).
TEST_F(FormatTest, LasFarFromTheOriginKeepsItsMillimetres) {
  LasHeader h;
  h.legacy_points = 3;
  h.scale = {0.001, 0.001, 0.001};
  h.offset = {500000, 4000000, 0};
  const PointCloud cloud = pss::read_las(write("utm.las", las_header(h) + las_record_2(123456, 789012, 45678, {}) +
                                                          las_record_2(123457, 789011, 45679, {}) +
                                                          las_record_2(124000, 788000, 46000, {})));
  ASSERT_EQ(cloud.size(), 3u);
  const glm::dvec3 expected[] = {{500123.456, 4000789.012, 45.678}, {500123.457, 4000789.011, 45.679},
                                 {500124, 4000788, 46}};
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(cloud.world(i)[k], expected[i][k], 1e-6) << i << k;
  EXPECT_FALSE(cloud.has_colors()) << "RGB fields all 0 are no colours (they would render black)";
}

TEST_F(FormatTest, Las14Format7ExtraBytesAnd16BitColours) {
  LasHeader h;
  h.minor = 4;
  h.format = 7;
  h.record_length = 36 + 4;  // 4 extra bytes per point
  h.points = 2;
  h.scale = {0.001, 0.001, 0.001};
  h.offset = {-5, 0, 0.5};
  const auto record = [](std::int32_t x, std::int32_t y, std::int32_t z, std::array<std::uint16_t, 3> rgb) {
    Bytes b;
    // intensity, return bits, class flags (withheld), class 2 (ground), user data, angle, source, time
    b.put(x).put(y).put(z).put(std::uint16_t(9)).put(std::uint8_t(0)).put(std::uint8_t(0b100)).put(std::uint8_t(2));
    b.zeros(1).put(std::int16_t(0)).put(std::uint16_t(3)).put(1.5);
    for (std::uint16_t c : rgb) b.put(c);
    return b.str() + "XTRA";
  };
  const std::string file = las_header(h) + record(5000, 250, -500, {65535, 257, 0}) + record(0, -1000, 0, {32896, 0, 65280});
  const PointCloud cloud = pss::read_las(write("b.las", file));
  EXPECT_EQ(cloud.positions, (std::vector<vec3>{{0, 0.25f, 0}, {-5, -1, 0.5f}}));
  EXPECT_EQ(cloud.colors, (std::vector<Rgb8>{{255, 1, 0}, {128, 0, 254}}));
  ASSERT_EQ(cloud.scalars.size(), 2u);
  EXPECT_EQ(cloud.scalars[0].values, (std::vector<double>{9, 9}));
  EXPECT_EQ(cloud.scalars[1].values, (std::vector<double>{2, 2})) << "formats 6-10 keep the class in byte 16";
}

TEST_F(FormatTest, LasWithoutColoursAndTheLegacyCountIn14) {
  LasHeader h;
  h.minor = 4;
  h.format = 1;
  h.record_length = 28;
  h.legacy_points = 1;  // formats 0-5 may keep it
  h.points = 1;
  const PointCloud cloud = pss::read_las(write("c.las", las_header(h) + Bytes().put(100).put(200).put(300).zeros(16).str()));
  EXPECT_EQ(cloud.positions, std::vector<vec3>{vec3(1, 2, 3)});
  EXPECT_FALSE(cloud.has_colors());
}

TEST_F(FormatTest, LasErrors) {
  const auto with = [](auto change) {
    LasHeader h;
    h.legacy_points = 2;
    change(h);
    return las_header(h) + las_record_2(1, 2, 3, {0, 0, 0}) + las_record_2(4, 5, 6, {0, 0, 0});
  };
  std::string bad_version = with([](LasHeader&) {});
  bad_version[24] = 2;
  const std::pair<std::string, std::string> cases[] = {
      {"LASX" + std::string(300, '\0'), "not a LAS file (no 'LASF' signature)"},
      {with([](LasHeader&) {}).substr(0, 200), "truncated: 200 bytes, less than a LAS header"},
      {bad_version, "unsupported LAS version 2.2 (1.0 to 1.4 are read)"},
      {with([](LasHeader& h) { h.legacy_points = 3; }), "truncated: 3 points of 26 bytes need more than the 52 bytes"},
      {with([](LasHeader& h) { h.legacy_points = 4000000000u; }), "truncated: 4000000000 points"},
      {with([](LasHeader& h) { h.record_length = 25; }), "point records of 25 bytes are shorter than format 2's 26"},
      {with([](LasHeader& h) { h.format = 2 | 0x80; }), "compressed LAS (LAZ) is not supported"},
      {with([](LasHeader& h) { h.format = 11; }), "unknown point data record format 11"},
      {with([](LasHeader& h) { h.data_offset = 100000; }), "offset to point data 100000 is not between"},
      {with([](LasHeader& h) { h.data_offset = 100; }), "offset to point data 100 is not between"},
      {with([](LasHeader& h) { h.scale[1] = 0; }), "invalid scale 0 or offset 0 of axis y"},
      {with([](LasHeader& h) { h.offset[2] = std::numeric_limits<double>::quiet_NaN(); }), "of axis z"},
      {with([](LasHeader& h) { h.scale[0] = 1e300; }), "point 0 lies beyond float's range"},
      {with([](LasHeader& h) { h.legacy_points = 0; }), "no points"},
      {with([](LasHeader& h) { h.minor = 4, h.points = 3; }), "the legacy point count 2 differs from the 64-bit one 3"},
  };
  for (const auto& [bytes, problem] : cases) expect_refused(pss::read_las, write("bad.las", bytes), problem);
  std::string short_header = with([](LasHeader&) {});
  short_header[94] = char(200);  // header size 200 < 227
  expect_refused(pss::read_las, write("short.las", short_header), "header size 200 is not between LAS 1.2's 227");
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

// ---------------------------------------------------------------------------------------
// PLY scalar properties

using pss::ScalarProperty;
using pss::ScalarType;

void expect_scalars(const PointCloud& cloud, const std::vector<ScalarProperty>& expected) {
  ASSERT_EQ(cloud.scalars.size(), expected.size());
  for (std::size_t k = 0; k < expected.size(); ++k) {
    EXPECT_EQ(cloud.scalars[k].name, expected[k].name) << k;
    EXPECT_EQ(cloud.scalars[k].type, expected[k].type) << expected[k].name;
    EXPECT_EQ(cloud.scalars[k].values, expected[k].values) << expected[k].name;
  }
}

// Every type at its extremes, a sized type name, and a list between them that is skipped.
const std::string kScalarProperties =
    "element vertex 2\nproperty float x\nproperty float y\nproperty float z\nproperty uint8 label\n"
    "property list uchar int ids\nproperty int count\nproperty float intensity\nproperty double confidence\n"
    "property char offset\nproperty ushort u16\nproperty uint u32\nend_header\n";

const std::vector<ScalarProperty> kScalarsWritten = {
    {"label", ScalarType::uint8, {255, 0}},
    {"count", ScalarType::int32, {-2147483648.0, 2147483647}},
    {"intensity", ScalarType::float32, {0.25, double(0.1f)}},  // the text's 0.1 rounded to float
    {"confidence", ScalarType::float64, {0.1, 1e300}},
    {"offset", ScalarType::int8, {-128, 127}},
    {"u16", ScalarType::uint16, {65535, 0}},
    {"u32", ScalarType::uint32, {4294967295.0, 0}},
};

std::string scalars_binary() {
  Bytes b;
  b.text("ply\nformat binary_little_endian 1.0\n" + kScalarProperties);
  b.put(1.f).put(2.f).put(3.f).put(std::uint8_t(255)).put(std::uint8_t(2)).put(7).put(8).put(-2147483647 - 1);
  b.put(0.25f).put(0.1).put(std::int8_t(-128)).put(std::uint16_t(65535)).put(std::uint32_t(4294967295u));
  b.put(4.f).put(5.f).put(6.f).put(std::uint8_t(0)).put(std::uint8_t(0)).put(2147483647);
  b.put(0.1f).put(1e300).put(std::int8_t(127)).put(std::uint16_t(0)).put(std::uint32_t(0));
  return b.str();
}

TEST_F(FormatTest, PlyScalarsRoundTripWithTheirTypes) {
  const std::string ascii = "ply\nformat ascii 1.0\n" + kScalarProperties +
                            "1 2 3 255 2 7 8 -2147483648 0.25 0.1 -128 65535 4294967295\n"
                            "4 5 6 0 0 2147483647 0.1 1e300 127 0 0\n";
  for (const std::string& bytes : {ascii, scalars_binary()}) {
    const PointCloud cloud = pss::read_ply(write("s.ply", bytes));
    EXPECT_EQ(cloud.positions, (std::vector<vec3>{{1, 2, 3}, {4, 5, 6}}));
    expect_scalars(cloud, kScalarsWritten);
    pss::write_ply(path("out.ply"), cloud);
    // After the colours would be, in their types under their original names.
    EXPECT_NE(read(path("out.ply")).find("property float z\nproperty uchar label\nproperty int count\n"
                                         "property float intensity\nproperty double confidence\n"
                                         "property char offset\nproperty ushort u16\nproperty uint u32\n"
                                         "end_header\n"),
              std::string::npos);
    expect_scalars(pss::read_ply(path("out.ply")), kScalarsWritten);
  }
}

// A file is read a part of 65,536 points at a time (io/point_stream.hpp): a scalar's values
// come out whole and in order across the parts.
TEST_F(FormatTest, PlyScalarsOfManyPartsComeOutWholeAndInOrder) {
  constexpr int n = 70000;
  std::string bytes = "ply\nformat binary_little_endian 1.0\nelement vertex " + std::to_string(n) +
                      "\nproperty float x\nproperty float y\nproperty float z\nproperty float intensity\nend_header\n";
  for (int i = 0; i < n; ++i) {
    const float v[4] = {float(i % 300), float(i / 300), 0.0f, float(i)};
    bytes.append(reinterpret_cast<const char*>(v), sizeof v);
  }
  const PointCloud cloud = pss::read_point_cloud(write("many.ply", bytes));
  ASSERT_EQ(cloud.size(), std::size_t(n));
  ASSERT_EQ(cloud.scalars.size(), 1u);
  ASSERT_EQ(cloud.scalars[0].values.size(), std::size_t(n));
  for (int i = 0; i < n; ++i) ASSERT_EQ(cloud.scalars[0].values[std::size_t(i)], double(i)) << i;
}

// The formats read a part at a time, so that a cloud larger than memory is tiled.
TEST_F(FormatTest, TheStreamedFormats) {
  for (const char* name : {"a.ply", "a.xyz", "a.txt", "a.pts", "a.pwn", "a.las", "A.PTS"})
    EXPECT_TRUE(pss::has_point_stream(name)) << name;
  for (const char* name : {"a.obj", "a.off", "a.stl", "a.pcd"}) EXPECT_FALSE(pss::has_point_stream(name)) << name;
}

TEST_F(FormatTest, PlyScalarsAreKeptOnceEachAndNeverUnderAReadName) {
  // nx ny without nz are no normals, and not scalars either: a second 'x' neither; the
  // second 'intensity' is skipped; alpha is an ordinary scalar.
  const PointCloud cloud = pss::read_ply(write(
      "k.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\n"
               "property float nx\nproperty float ny\nproperty float x\nproperty float intensity\n"
               "property uchar red\nproperty uchar green\nproperty uchar blue\nproperty uchar alpha\n"
               "property float intensity\nend_header\n1 2 3 0 1 9 0.5 10 20 30 40 0.75\n"));
  EXPECT_FALSE(cloud.has_normals());
  EXPECT_EQ(cloud.positions, std::vector<vec3>{vec3(1, 2, 3)});
  EXPECT_EQ(cloud.colors, std::vector<Rgb8>{Rgb8(10, 20, 30)});
  expect_scalars(cloud, {{"intensity", ScalarType::float32, {0.5}}, {"alpha", ScalarType::uint8, {40}}});

  // Only the first 64 are kept; the rest are skipped like lists.
  std::string header =
      "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\n";
  std::string values = "1 2 3";
  for (int k = 0; k < 70; ++k) {
    header += "property short s" + std::to_string(k) + "\n";
    values += " " + std::to_string(k);
  }
  const PointCloud many = pss::read_ply(write("m.ply", header + "end_header\n" + values + "\n"));
  ASSERT_EQ(many.scalars.size(), 64u);
  EXPECT_EQ(many.scalars.back().name, "s63");
  EXPECT_EQ(many.scalars.back().values, std::vector<double>{63});
}

TEST_F(FormatTest, PlyScalarErrors) {
  const std::string header = "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\n"
                             "property float z\nproperty uchar label\nproperty int count\nend_header\n";
  expect_refused(pss::read_ply, write("a.ply", header + "1 2 3 4 5\n1 2 3 4 3.5\n"),
                 "line 11: value 3.5 of 'count' does not fit its type int");
  expect_refused(pss::read_ply, write("b.ply", header + "1 2 3 256 5\n"),
                 "line 10: value 256 of 'label' does not fit its type uchar");
  expect_refused(pss::read_ply, write("c.ply", header + "1 2 3 4 5\n1 2 3 4\n"),
                 "truncated: expected 2 vertices, read 1");
  const std::string binary = scalars_binary();
  expect_refused(pss::read_ply, write("d.ply", binary.substr(0, binary.size() - 3)),
                 "truncated: expected 2 vertices, read 1");
  // A count no file could hold: the scalars too are reserved for what the bytes can hold.
  std::string lying = binary;
  lying.replace(lying.find("vertex 2"), 8, "vertex 4000000000000");
  expect_refused(pss::read_ply, write("e.ply", lying), "truncated: expected 4000000000000 vertices, read 2");
}

TEST_F(FormatTest, PlyWriterKeepsEveryNameOnce) {
  PointCloud cloud;
  cloud.positions = {{1, 2, 3}};
  cloud.scalars = {{"status", ScalarType::uint8, {7}}, {"input_status", ScalarType::float32, {0.5}}};
  const std::int32_t status[] = {2};
  const pss::PlyIntProperty extra[] = {{"status", status}};
  // The input's status is renamed, past a name the input already has.
  pss::write_ply(path("s.ply"), cloud, extra);
  EXPECT_NE(read(path("s.ply")).find("property float z\nproperty uchar input_input_status\n"
                                     "property float input_status\nproperty int status\nend_header\n"),
            std::string::npos)
      << read(path("s.ply"));
  expect_scalars(pss::read_ply(path("s.ply")), {{"input_input_status", ScalarType::uint8, {7}},
                                                {"input_status", ScalarType::float32, {0.5}},
                                                {"status", ScalarType::int32, {2}}});

  const auto refused = [&](const PointCloud& bad, const std::string& problem) {
    EXPECT_NE(pss::test::error_of([&] { pss::write_ply(path("bad.ply"), bad); }).find(problem), std::string::npos)
        << problem;
    EXPECT_FALSE(std::filesystem::exists(path("bad.ply")));
  };
  PointCloud bad = cloud;
  bad.scalars[1].name = "x";
  refused(bad, "cannot write: two properties named 'x'");
  bad.scalars[1].name = "in tensity";
  refused(bad, "cannot write: invalid property name 'in tensity'");
  bad = cloud;
  bad.scalars[0].values = {256};
  refused(bad, "cannot write: value 256 of 'status' does not fit its type uchar");
  bad.scalars[0].values = {1, 2};
  refused(bad, "cannot write: 1 positions but 2 values of 'status'");
}

// Projection moves points but keeps their order: the scalars stay with them.
TEST_F(FormatTest, ProjectionKeepsScalars) {
  PointCloud cloud;
  ScalarProperty label{"label", ScalarType::int32, {}};
  for (int i = 0; i < 20; ++i)
    for (int j = 0; j < 20; ++j) {
      cloud.positions.emplace_back(0.1f * float(i), 0.1f * float(j), 0.01f * float((i * 7 + j * 3) % 5));
      label.values.push_back(i * 20 + j);
    }
  cloud.scalars = {label};
  pss::Stats stats;
  const pss::CloudProjection out =
      pss::project_cloud(cloud, pss::ProjectionParams::from_h(0.2f), pss::Backend::cpu, stats);
  expect_scalars(out.cloud, cloud.scalars);
}

// ---------------------------------------------------------------------------------------
// read_point_cloud

TEST_F(FormatTest, ReadPointCloudDispatchesEveryFormatCaseInsensitively) {
  LasHeader las;
  las.legacy_points = 1;
  const std::pair<std::string, std::string> files[] = {
      {"m.OBJ", "v 1 2 3\n"},
      {"m.Off", "OFF\n1 0 0\n1 2 3\n"},
      {"p.PWN", "1 2 3 0 0 1\n"},
      {"m.Stl", "solid\nfacet normal 0 0 1\nouter loop\nvertex 1 2 3\nvertex 1 2 3\nvertex 1 2 3\nendloop\n"
                "endfacet\nendsolid\n"},
      {"c.PcD", "FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nPOINTS 1\nDATA ascii\n1 2 3\n"},
      {"s.LAS", las_header(las) + las_record_2(100, 200, 300, {0, 0, 0})},
  };
  for (const auto& [name, bytes] : files) {
    const PointCloud cloud = pss::read_point_cloud(write(name, bytes));
    EXPECT_EQ(cloud.positions, std::vector<vec3>{vec3(1, 2, 3)}) << name;
  }
  expect_refused(pss::read_point_cloud, write("s.laz", "LASF"),
                 "compressed LAS (LAZ) is not supported; decompress it to .las first (laszip, PDAL)");
}

}  // namespace
