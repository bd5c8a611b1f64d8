// The output format follows the file's extension (issue 12): each format is read back by its
// own library and compared with a frame or cloud whose values the test sets, and a name pss
// does not write is refused before anything is written.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "pss/core/error.hpp"
#include "pss/io/point_cloud_file.hpp"
#include "pss/io/xyz.hpp"
#include "pss/render/frame_outputs.hpp"
#include "support/cli.hpp"
#include "support/output_readers.hpp"

namespace pss {
namespace {

namespace fs = std::filesystem;
constexpr float kInf = std::numeric_limits<float>::infinity();

// sRGB 8-bit of a linear value (IEC 61966-2-1), written out here as the truth.
int srgb8(float linear) {
  const double s = linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(double(linear), 1 / 2.4) - 0.055;
  return int(std::lround(s * 255));
}

// 4x2 pixels, two of them hit: (1, 0) at t = 2.5 with a normal toward the camera, (2, 1)
// at t = 7.25 with a normal away from it. The misses show a grey background.
const vec3 kBackground(0.2f), kFirst(1.0f, 0.05f, 0.0f), kSecond(0.25f, 0.5f, 0.75f);
RenderedFrame known_frame() {
  RenderedFrame f;
  f.camera.width = 4;
  f.camera.height = 2;
  f.image = Image(4, 2);
  f.hits.resize(8);
  for (vec3& p : f.image.pixels) p = kBackground;
  const auto hit = [&](int x, int y, float t, vec3 normal, vec3 colour) {
    Hit& h = f.hits[std::size_t(y * 4 + x)];
    h.flags = kHitFound;
    h.t = t;
    h.normal = normal;
    h.point = f.camera.eye + t * f.camera.primary_ray(x, y).dir;
    f.image.at(x, y) = colour;
  };
  hit(1, 0, 2.5f, vec3(0, 0, 1), kFirst);
  hit(2, 1, 7.25f, vec3(0, 0, -1), kSecond);
  return f;
}

bool is_hit(int x, int y) { return (x == 1 && y == 0) || (x == 2 && y == 1); }

class OutputFormats : public test::CliTest {
 protected:
  std::vector<std::string> listing() const {
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(dir_)) names.push_back(entry.path().filename().string());
    return names;
  }
  // A refused write: a one-line pss::Error naming the file and `problem`, and nothing in the folder.
  template <class F>
  void expect_refused(F&& write, const std::string& file, const std::string& problem) {
    const std::string message = test::error_of(write);
    EXPECT_NE(message.find(file + ": "), std::string::npos) << message;
    EXPECT_NE(message.find(problem), std::string::npos) << message;
    EXPECT_TRUE(listing().empty());
  }
};

TEST_F(OutputFormats, PngHoldsTheFramesSrgbColours) {
  write_frame_image(path("f.png"), known_frame(), false);
  const test::Image8 png = test::read_image8(path("f.png"));
  ASSERT_EQ(png.channels, 3);
  ASSERT_EQ(png.width, 4);
  ASSERT_EQ(png.height, 2);
  EXPECT_EQ(read(path("f.png")).substr(1, 3), "PNG");
  for (int c = 0; c < 3; ++c) {
    EXPECT_EQ(png.at(1, 0, c), srgb8(kFirst[c]));
    EXPECT_EQ(png.at(2, 1, c), srgb8(kSecond[c]));
    EXPECT_EQ(png.at(0, 0, c), srgb8(kBackground[c]));
  }
}

TEST_F(OutputFormats, TransparentPngHasAlphaOnlyWhereTheRayHit) {
  write_frame_image(path("f.png"), known_frame(), true);
  const test::Image8 png = test::read_image8(path("f.png"));
  ASSERT_EQ(png.channels, 4);
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 4; ++x) EXPECT_EQ(png.at(x, y, 3), is_hit(x, y) ? 255 : 0) << x << "," << y;
  EXPECT_EQ(png.at(2, 1, 2), srgb8(kSecond[2]));
  EXPECT_EQ(png.at(3, 1, 0), srgb8(kBackground[0])) << "a transparent pixel keeps its colour (straight alpha)";
}

TEST_F(OutputFormats, JpegHoldsTheFramesColours) {
  RenderedFrame f = known_frame();
  // JPEG blurs edges: one flat colour, 16x16, decodes close to it.
  f.camera.width = f.camera.height = 16;
  f.image = Image(16, 16);
  for (vec3& p : f.image.pixels) p = kSecond;
  f.hits.assign(256, Hit{});
  write_frame_image(path("f.JPEG"), f, false);
  EXPECT_EQ(read(path("f.JPEG")).substr(0, 3), "\xff\xd8\xff");
  const test::Image8 jpeg = test::read_image8(path("f.JPEG"));
  ASSERT_EQ(jpeg.channels, 3);
  ASSERT_EQ(jpeg.width, 16);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(jpeg.at(8, 8, c), srgb8(kSecond[c]), 3) << c;
  // At the quality --help names (kJpegQuality, 95): the luminance table's first step is the
  // standard table's 16 scaled by (200 − 2·95) %, rounded: 2 (quality 90 would give 3).
  const std::string bytes = read(path("f.JPEG"));
  const std::size_t table = bytes.find("\xff\xdb");
  ASSERT_NE(table, std::string::npos);
  ASSERT_LT(table + 5, bytes.size());
  EXPECT_EQ(int(std::uint8_t(bytes[table + 5])), (16 * (200 - 2 * kJpegQuality) + 50) / 100);
}

TEST_F(OutputFormats, ExrHoldsLinearColourAlphaDepthAndNormals) {
  write_frame_image(path("f.exr"), known_frame(), false);
  const test::ExrImage exr = test::read_exr(path("f.exr"));
  std::set<std::string> names;
  for (const auto& [name, values] : exr.channels) names.insert(name);
  EXPECT_EQ(names, (std::set<std::string>{"R", "G", "B", "A", "Z", "N.X", "N.Y", "N.Z"}));
  ASSERT_EQ(exr.width, 4);
  ASSERT_EQ(exr.height, 2);
  // Colour is half: 11 significant bits.
  EXPECT_NEAR(exr.at("R", 1, 0), kFirst.x, 1e-3);
  EXPECT_NEAR(exr.at("G", 1, 0), kFirst.y, 1e-4);
  EXPECT_NEAR(exr.at("B", 2, 1), kSecond.z, 1e-3);
  EXPECT_NEAR(exr.at("R", 0, 0), kBackground.x, 1e-3);
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 4; ++x) {
      EXPECT_EQ(exr.at("A", x, y), 1.0f);
      if (is_hit(x, y)) continue;
      EXPECT_EQ(exr.at("Z", x, y), kInf) << x << "," << y;
      EXPECT_EQ(exr.at("N.Z", x, y), 0.0f);
    }
  EXPECT_EQ(exr.at("Z", 1, 0), 2.5f);
  EXPECT_EQ(exr.at("Z", 2, 1), 7.25f);
  // Both normals face the camera (+z, the camera looks along -z): the second one turned.
  EXPECT_EQ(exr.at("N.Z", 1, 0), 1.0f);
  EXPECT_EQ(exr.at("N.Z", 2, 1), 1.0f);
  EXPECT_EQ(exr.at("N.X", 2, 1), 0.0f);
}

TEST_F(OutputFormats, TransparentExrIsPremultiplied) {
  write_frame_image(path("f.exr"), known_frame(), true);
  const test::ExrImage exr = test::read_exr(path("f.exr"));
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 4; ++x) {
      EXPECT_EQ(exr.at("A", x, y), is_hit(x, y) ? 1.0f : 0.0f) << x << "," << y;
      if (!is_hit(x, y)) EXPECT_EQ(exr.at("R", x, y), 0.0f);
    }
  EXPECT_NEAR(exr.at("G", 2, 1), kSecond.y, 1e-3);
}

TEST_F(OutputFormats, AnImageNamedForAnotherFormatIsRefused) {
  const RenderedFrame f = known_frame();
  expect_refused([&] { write_frame_image(path("f.gif"), f, false); }, path("f.gif"),
                 "cannot write an image as '.gif': name it .png, .jpg, .jpeg or .exr");
  expect_refused([&] { write_frame_image(path("f.ply"), f, false); }, path("f.ply"), "'.ply'");
  expect_refused([&] { write_frame_image(path("f"), f, false); }, path("f"), "without an extension");
  expect_refused([&] { write_frame_image(path("f.jpg"), f, true); }, path("f.jpg"), "no alpha");
}

// Floats whose shortest decimal needs all nine digits, and extremes.
PointCloud awkward_cloud() {
  PointCloud c;
  c.positions = {vec3(0.1f, 1.0f / 3.0f, -2.0f / 7.0f), vec3(16777215.0f, 1.17549435e-38f, -3.40282347e38f),
                 vec3(std::nextafter(1.0f, 2.0f), 123456.789f, -0.0f)};
  c.normals = {vec3(0, 0, 1), vec3(0.6f, 0.8f, 0), vec3(1.0f / 3.0f, 2.0f / 3.0f, 2.0f / 3.0f)};
  return c;
}

// The lines of a text file split into floats by strtof, as any tool would read them.
std::vector<std::vector<float>> parse_floats(const std::string& text) {
  std::vector<std::vector<float>> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    std::istringstream words(line);
    lines.emplace_back();
    for (std::string word; words >> word;) lines.back().push_back(std::strtof(word.c_str(), nullptr));
  }
  return lines;
}

TEST_F(OutputFormats, XyzRoundTripsEveryFloat) {
  const PointCloud cloud = awkward_cloud();
  write_point_cloud(path("c.XYZ"), cloud);
  const auto lines = parse_floats(read(path("c.XYZ")));
  ASSERT_EQ(lines.size(), cloud.size());
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    ASSERT_EQ(lines[i].size(), 6u);
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(std::bit_cast<std::uint32_t>(lines[i][k]), std::bit_cast<std::uint32_t>(cloud.positions[i][k]));
      EXPECT_EQ(lines[i][3 + k], cloud.normals[i][k]);
    }
  }
  EXPECT_EQ(read_xyz(path("c.XYZ")).positions, cloud.positions);
}

TEST_F(OutputFormats, XyzWithoutNormalsHasThreeColumns) {
  PointCloud cloud = awkward_cloud();
  cloud.normals.clear();
  write_point_cloud(path("c.xyz"), cloud);
  const auto lines = parse_floats(read(path("c.xyz")));
  ASSERT_EQ(lines.size(), 3u);
  EXPECT_EQ(lines[2], (std::vector<float>{cloud.positions[2].x, cloud.positions[2].y, cloud.positions[2].z}));
}

TEST_F(OutputFormats, PlyKeepsTheExtraProperties) {
  const PointCloud cloud = awkward_cloud();
  const std::vector<std::int32_t> label = {7, -1, 2};
  const PlyIntProperty extra[] = {{"label", label}};
  write_point_cloud(path("c.Ply"), cloud, extra);
  const test::PlyColumns ply = test::read_ply_columns(path("c.Ply"));
  EXPECT_EQ(ply.header.at(1), "format binary_little_endian 1.0");
  EXPECT_EQ(ply.columns.at("label"), (std::vector<double>{7, -1, 2}));
  EXPECT_EQ(ply.columns.at("y")[0], double(1.0f / 3.0f));
}

TEST_F(OutputFormats, PointsNamedForAnotherFormatAreRefused) {
  const PointCloud cloud = awkward_cloud();
  expect_refused([&] { write_point_cloud(path("c.png"), cloud); }, path("c.png"),
                 "cannot write a point cloud as '.png': name it .ply or .xyz");
  expect_refused([&] { write_point_cloud(path("c.txt"), cloud); }, path("c.txt"), "'.txt'");
}

TEST_F(OutputFormats, HitsAsXyzAreTheHitPointsAndCameraFacingNormals) {
  const RenderedFrame f = known_frame();
  write_hits(path("h.xyz"), f);
  const auto lines = parse_floats(read(path("h.xyz")));
  ASSERT_EQ(lines.size(), 2u);
  const vec3 second = f.hits[6].point;
  EXPECT_EQ(lines[1], (std::vector<float>{second.x, second.y, second.z, 0, 0, 1}));
}

}  // namespace
}  // namespace pss
