// `pss volume` as a user meets it on a real scan (issue 7): the camera frames the surface,
// an iso-value outside the data is refused with the data's range, a render that hits
// nothing says so, and flags that do not apply are refused.
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "pss/io/ply.hpp"
#include "support/cli.hpp"
#include "support/volumes.hpp"

namespace pss {
namespace {

namespace fs = std::filesystem;

class VolumeCliTest : public ::testing::Test {
 protected:
  // A ball of radius 4 voxels in a corner of a 64³ uint8 volume of zeros.
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("pss_volume_cli_test_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
    write("ball.raw", test::sphere_distance(vec3(12.0f, 14.0f, 10.0f), 4.0f));
  }
  void TearDown() override { fs::remove_all(dir_); }

  // 100 − 40·f as uint8 over 64³ voxels: the surface f = 0 is the iso-value 100.
  void write(const std::string& name, const test::Field& f) const {
    std::ofstream(dir_ / name, std::ios::binary) << test::uint8_raw_bytes(f, ivec3(64));
  }
  std::string input(const std::string& name = "ball.raw") const {
    return (dir_ / name).string() + " --dims 64x64x64 --type uint8";
  }
  fs::path dir_;
};

// The ball spans an eighth of the box's width: framed as the box, it would be a speck of
// a few pixels; framed as the surface, it fills a good part of the image.
TEST_F(VolumeCliTest, TheCameraFramesTheSurfaceNotTheBox) {
  const std::string hits = (dir_ / "hits.ply").string();
  const test::CliResult r = test::run_pss("volume " + input() + " --iso 100 --size 64x64 -o " +
                                          (dir_ / "b.png").string() + " --hits " + hits);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_GT(read_ply(hits).size(), 64u * 64u / 10);  // framed as the box: about 20 pixels
}

TEST_F(VolumeCliTest, AnIsoValueOutsideTheDataIsRefusedWithItsRange) {
  const fs::path png = dir_ / "b.png";
  const test::CliResult r = test::run_pss("volume " + input() + " --iso 300 -o " + png.string());
  EXPECT_NE(r.exit_code, 0);
  EXPECT_EQ(test::line_count(r.err), 1) << r.err;
  EXPECT_NE(r.err.find((dir_ / "ball.raw").string() + ": the iso-value 300"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("[0, 255]"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(png));
}

// Two small balls in opposite corners: the framing spans both, and the one ray of a 1x1
// image passes through the middle, between them.
TEST_F(VolumeCliTest, ARenderThatHitsNothingSaysSo) {
  const test::Field corner_a = test::sphere_distance(vec3(6.0f), 2.5f), corner_b = test::sphere_distance(vec3(57.0f), 2.5f);
  write("corners.raw", {[&](vec3 p) { return std::min(corner_a.value(p), corner_b.value(p)); },
                        [&](vec3 p) { return corner_a.value(p) < corner_b.value(p) ? corner_a.gradient(p) : corner_b.gradient(p); },
                        0.0f});
  const test::CliResult r = test::run_pss("volume " + input("corners.raw") + " --iso 100 --size 1x1 -o " +
                                          (dir_ / "c.png").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("no ray hit the surface"), std::string::npos) << r.err;
  const test::CliResult hit = test::run_pss("volume " + input() + " --iso 100 --size 1x1 -o " + (dir_ / "b.png").string());
  EXPECT_EQ(hit.err.find("no ray hit"), std::string::npos) << hit.err;
}

TEST_F(VolumeCliTest, ThresholdIsForGradientSurfacesOnly) {
  const test::CliResult r =
      test::run_pss("volume " + input() + " --iso 100 --threshold 5 -o " + (dir_ / "b.png").string());
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find("--threshold"), std::string::npos) << r.err;
}

// Raw volume flags given with a file they do not describe are refused as such, in one line
// naming the file and why, by every command that reads volumes, and nothing is written:
// - a file with a header describes its own voxels (not "a raw volume needs --dims");
// - a point cloud is no raw volume (a new user's trial: `pss mesh cloud.ply --dims 32x32x32`
//   read the PLY's bytes as voxels and asked for --iso).
TEST_F(VolumeCliTest, RawFlagsWithAFileTheyDoNotDescribeAreRefusedAsSuch) {
  const std::string engine = std::string(PSS_SOURCE_DIR) + "/data/engine_256x256x128_uint8.nrrd";
  const std::string bunny = std::string(PSS_SOURCE_DIR) + "/data/bun_zipper.ply";
  const std::string out = (dir_ / "o").string();
  const struct {
    std::string file, raw, why;
  } cases[] = {{engine, "--type uint16", "the file's header describes the volume; drop --dims"},
               {bunny, "--dims 32x32x32", "a point cloud, not a volume"}};
  for (const auto& c : cases)
    for (const std::string& command :
         {"volume " + c.file + " --iso 100 " + c.raw + " -o " + out + ".png",
          "extract " + c.file + " --iso 100 " + c.raw + " -o " + out + ".ply",
          "mesh " + c.file + " --iso 100 " + c.raw + " -o " + out + ".ply", "info " + c.file + " --skip 4"}) {
      const test::CliResult r = test::run_pss(command);
      EXPECT_NE(r.exit_code, 0) << command;
      EXPECT_EQ(test::line_count(r.err), 1) << command << "\n" << r.err;
      EXPECT_NE(r.err.find(c.file + ": " + c.why), std::string::npos) << command << "\n" << r.err;
      EXPECT_FALSE(fs::exists(out + ".png") || fs::exists(out + ".ply")) << command;
    }
}

// --stats with an empty name is refused, not taken as no --stats (the same trial: the mesh
// was written and no statistics, without a word).
TEST_F(VolumeCliTest, AnEmptyStatsNameIsRefused) {
  const std::string bunny = std::string(PSS_SOURCE_DIR) + "/data/bun_zipper.ply";
  const std::string out = (dir_ / "o.ply").string();
  for (const std::string& command : {"mesh " + bunny + " -o " + out + " --stats ''",
                                     "project " + bunny + " -o " + out + " --stats ''"}) {
    const test::CliResult r = test::run_pss(command);
    EXPECT_NE(r.exit_code, 0) << command;
    EXPECT_NE(r.err.find("--stats: an empty name is no file"), std::string::npos) << command << "\n" << r.err;
    EXPECT_FALSE(fs::exists(out)) << command;
  }
}
}  // namespace
}  // namespace pss
