// Every pss output flag writes the format its file's name says (issue 12): images of render
// and volume as PNG, JPEG or EXR, points of project, extract and --hits as PLY or XYZ; a name
// of the wrong kind is a one-line usage error naming the flag and the file, before any work
// and with no output; project's PLY says how each point's projection ended.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

#include "pss/io/ply.hpp"
#include "pss/render/camera_file.hpp"
#include "support/cli.hpp"
#include "support/output_readers.hpp"
#include "support/shapes.hpp"
#include "support/volumes.hpp"

namespace pss {
namespace {

class CliOutputFormats : public test::CliTest {
 protected:
  void SetUp() override {
    CliTest::SetUp();
    test::SampleOptions o;
    o.count = 2000;
    write_ply(path("sphere.ply"), test::sample(test::Sphere{}, o));
  }
  std::string render(const std::string& args) const { return "render " + path("sphere.ply") + " --size 32x32 " + args; }
  // A ball in a 32³ uint8 volume, as the volume CLI tests make it.
  std::string volume_input() const {
    write("ball.raw", test::uint8_raw_bytes(test::sphere_distance(vec3(16.0f), 6.0f), ivec3(32)));
    return path("ball.raw") + " --dims 32x32x32 --type uint8 --iso 100";
  }
  void expect_runs(const std::string& args) const {
    const test::CliResult r = test::run_pss(args);
    ASSERT_EQ(r.exit_code, 0) << args << "\n" << r.err;
  }
};

TEST_F(CliOutputFormats, RenderWritesTheFormatOfTheExtension) {
  expect_runs(render("-o " + path("o.jpg")));
  EXPECT_EQ(read(path("o.jpg")).substr(0, 3), "\xff\xd8\xff");
  EXPECT_EQ(test::read_image8(path("o.jpg")).width, 32);
  expect_runs(render("-o " + path("o.EXR")));
  EXPECT_EQ(read(path("o.EXR")).substr(0, 4), "\x76\x2f\x31\x01");
  expect_runs(render("-o " + path("o.png")));
  EXPECT_EQ(test::read_image8(path("o.png")).channels, 3);
}

TEST_F(CliOutputFormats, TransparentPngIsClearWhereTheRaysMissed) {
  expect_runs(render("--transparent -o " + path("o.png")));
  const test::Image8 png = test::read_image8(path("o.png"));
  ASSERT_EQ(png.channels, 4);
  EXPECT_EQ(png.at(0, 0, 3), 0) << "a corner misses the sphere";
  EXPECT_EQ(png.at(16, 16, 3), 255) << "the centre hits it";
  expect_runs("volume " + volume_input() + " --size 32x32 --transparent -o " + path("v.png"));
  const test::Image8 v = test::read_image8(path("v.png"));
  ASSERT_EQ(v.channels, 4);
  EXPECT_EQ(v.at(0, 0, 3), 0);
  EXPECT_EQ(v.at(16, 16, 3), 255);
}

// Z is the distance from the eye to the hit, for exactly the pixels --hits lists.
TEST_F(CliOutputFormats, ExrDepthIsTheDistanceToTheHit) {
  expect_runs(render("-o " + path("o.exr") + " --hits " + path("h.ply") + " --stats " + path("s.json")));
  const test::ExrImage exr = test::read_exr(path("o.exr"));
  const test::PlyColumns hits = test::read_ply_columns(path("h.ply"));
  const vec3 eye = read_camera_file(path("s.json"), 32, 32, glm::dvec3(0.0)).eye;
  const std::size_t n = hits.columns.at("px").size();
  ASSERT_GT(n, 100u);
  for (std::size_t i = 0; i < n; ++i) {
    const int x = int(hits.columns.at("px")[i]), y = int(hits.columns.at("py")[i]);
    const vec3 p(hits.columns.at("x")[i], hits.columns.at("y")[i], hits.columns.at("z")[i]);
    EXPECT_NEAR(exr.at("Z", x, y), glm::length(p - eye), 1e-5f * glm::length(p - eye)) << x << "," << y;
    EXPECT_EQ(exr.at("N.X", x, y), float(hits.columns.at("nx")[i]));
  }
  std::size_t finite = 0;
  for (float z : exr.channels.at("Z")) finite += std::isfinite(z);
  EXPECT_EQ(finite, n);
}

TEST_F(CliOutputFormats, AWrongExtensionIsAUsageErrorNamingTheFlag) {
  expect_clean_failure(render("-o " + path("o.gif")), "--output: " + path("o.gif") + ": cannot write an image as '.gif'",
                       path("o.gif"));
  expect_clean_failure(render("-o " + path("o.ply")), path("o.ply") + ": cannot write an image as '.ply'", path("o.ply"));
  expect_clean_failure(render("-o " + path("o.png") + " --hits " + path("h.png")),
                       "--hits: " + path("h.png") + ": cannot write a point cloud as '.png'", path("o.png"));
  expect_clean_failure(render("--transparent -o " + path("o.jpg")), "--transparent: " + path("o.jpg") + " is a JPEG",
                       path("o.jpg"));
  expect_clean_failure("project " + path("sphere.ply") + " -o " + path("p.png"), "--output: " + path("p.png"),
                       path("p.png"));
  expect_clean_failure("project " + path("sphere.ply") + " -o " + path("p"), path("p") + ": cannot write a point cloud without an extension",
                       path("p"));
  const std::string volume = volume_input();
  expect_clean_failure("extract " + volume + " -o " + path("e.png"), "--output: " + path("e.png"), path("e.png"));
  expect_clean_failure("volume " + volume + " -o " + path("v.xyz"), "--output: " + path("v.xyz"), path("v.xyz"));
  expect_clean_failure("volume " + volume + " --transparent -o " + path("v.jpeg"), "--transparent", path("v.jpeg"));
}

TEST_F(CliOutputFormats, ExtractAndHitsWriteXyz) {
  expect_runs("extract " + volume_input() + " -o " + path("e.xyz"));
  std::istringstream lines(read(path("e.xyz")));
  int count = 0;
  for (std::string line; std::getline(lines, line); ++count) {
    std::istringstream words(line);
    float x, y, z, nx, ny, nz;
    ASSERT_TRUE(words >> x >> y >> z >> nx >> ny >> nz) << line;
    EXPECT_NEAR(glm::length(vec3(x, y, z) - vec3(16.0f)), 6.0f, 0.3f);  // on the ball
  }
  EXPECT_GT(count, 50);
  expect_runs(render("-o " + path("o.png") + " --hits " + path("h.xyz")));
  EXPECT_GT(read(path("h.xyz")).size(), 1000u);
}

// Points far from the sphere have no neighbours within rho: status 2, the rest 0 or 1.
TEST_F(CliOutputFormats, ProjectedPlySaysHowEachProjectionEnded) {
  test::SampleOptions o;
  o.count = 2000;
  PointCloud cloud = test::sample(test::Sphere{}, o);
  const std::size_t on_sphere = cloud.size();
  for (float x : {-3.0f, 3.0f}) cloud.positions.push_back(vec3(x, 3.0f, 0.0f));
  cloud.positions.push_back(vec3(0.0f, -3.0f, 3.0f));
  cloud.normals.clear();  // none: RIMLS, the default, would fit a file's (these three have none)
  write_ply(path("outliers.ply"), cloud);
  expect_runs("project " + path("outliers.ply") + " --h 0.1 -o " + path("p.ply"));
  const test::PlyColumns ply = test::read_ply_columns(path("p.ply"));
  EXPECT_NE(std::find(ply.header.begin(), ply.header.end(), "property int status"), ply.header.end());
  const std::vector<double>& status = ply.columns.at("status");
  ASSERT_EQ(status.size(), cloud.size());
  int converged = 0;
  for (std::size_t i = 0; i < on_sphere; ++i) {
    EXPECT_TRUE(status[i] == 0 || status[i] == 1) << i << ": " << status[i];
    converged += status[i] == 0;
  }
  EXPECT_GT(converged, 1900);
  for (std::size_t i = on_sphere; i < cloud.size(); ++i) EXPECT_EQ(status[i], 2) << i;

  // The same points as text, without the status.
  expect_runs("project " + path("outliers.ply") + " --h 0.1 -o " + path("p.xyz"));
  std::istringstream lines(read(path("p.xyz")));
  std::size_t i = 0;
  for (std::string line; std::getline(lines, line); ++i) {
    std::istringstream words(line);
    float v[7];
    int k = 0;
    while (k < 7 && words >> v[k]) ++k;
    ASSERT_EQ(k, 6) << line;
    ASSERT_LT(i, cloud.size());
    EXPECT_EQ(v[0], float(ply.columns.at("x")[i]));
    EXPECT_EQ(v[5], float(ply.columns.at("nz")[i]));
  }
  EXPECT_EQ(i, cloud.size());
}

TEST_F(CliOutputFormats, HelpNamesTheExtensions) {
  for (const char* command : {"render", "volume"}) {
    const std::string help = test::run_pss(std::string(command) + " --help").out;
    for (const char* ext : {".png", ".jpg", ".exr", ".xyz", "--transparent"})
      EXPECT_NE(help.find(ext), std::string::npos) << command << " " << ext;
  }
  const std::string project = test::run_pss("project --help").out;
  EXPECT_NE(project.find("2 too few neighbours"), std::string::npos);
  EXPECT_NE(project.find(".xyz"), std::string::npos);
  EXPECT_NE(test::run_pss("extract --help").out.find(".xyz"), std::string::npos);
}


// --help gives the ranges the flags take (a new user's trial: --k said 0.5 < k < 1 and took
// 0.1; --fov, --zoom, --size did not say theirs) and which way extract's normals face.
TEST_F(CliOutputFormats, HelpGivesTheFlagsRangesAndTheNormalsSide) {
  const std::string render = test::run_pss("render --help").out;
  EXPECT_NE(render.find("--fov FLOAT:NUMBER in [1 - 170]"), std::string::npos) << render;
  EXPECT_NE(render.find("--zoom FLOAT:NUMBER in [0.001 - 1000]"), std::string::npos) << render;
  EXPECT_NE(render.find("each side from 1 to 16384"), std::string::npos) << render;
  const std::string volume = test::run_pss("volume --help").out;
  EXPECT_NE(volume.find("--k FLOAT:NUMBER in [0.05 - 1]"), std::string::npos) << volume;
  EXPECT_NE(volume.find("--radius FLOAT:NUMBER in [0.5 - 4]"), std::string::npos) << volume;
  EXPECT_EQ(volume.find("0.5 < k < 1 (paper"), std::string::npos) << volume;
  EXPECT_NE(test::run_pss("extract --help").out.find("toward higher values"), std::string::npos);
  EXPECT_NE(test::run_pss("project --help").out.find("--h FLOAT:POSITIVE"), std::string::npos);
}
}  // namespace
}  // namespace pss
