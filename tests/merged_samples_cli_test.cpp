// The merged samples from the command line (points/merged_samples.hpp, issue 26): pss info,
// project, render and mesh say how many points were merged, in their summaries and --stats;
// --support global merges none; tile by tile a cloud merges as in core.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <random>

#include <nlohmann/json.hpp>

#include "pss/io/ply.hpp"
#include "pss/io/point_cloud_file.hpp"
#include "support/cli.hpp"
#include "support/output_readers.hpp"
#include "support/shapes.hpp"

namespace pss {
namespace {

class MergedSamplesCli : public test::CliTest {
 protected:
  void SetUp() override {
    CliTest::SetUp();
    test::SampleOptions o;
    o.count = 60000;
    o.noise = 0.06f;  // h = 3σ: some 3,000 samples a support
    write_ply(path("noisy.ply"), test::sample(test::Torus{}, o));
  }
  std::int64_t merged_in(const std::string& stats) const {
    std::ifstream in(stats);
    return nlohmann::json::parse(in).at("points_merged").get<std::int64_t>();
  }
};

TEST_F(MergedSamplesCli, EveryCommandSaysHowManyPointsWereMerged) {
  const test::CliResult info = test::run_pss("info " + path("noisy.ply"));
  ASSERT_EQ(info.exit_code, 0) << info.err;
  EXPECT_NE(info.out.find("merged samples"), std::string::npos) << info.out;
  const std::string noisy = path("noisy.ply");
  for (const std::string& command : {"project " + noisy + " -o " + path("o.ply"),
                                     "render " + noisy + " -o " + path("o.png") + " --size 32x32",
                                     "mesh " + noisy + " -o " + path("o.ply") + " --cell 0.08"}) {
    SCOPED_TRACE(command);
    const test::CliResult r = test::run_pss(command + " --stats " + path("s.json"));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("points merged into samples"), std::string::npos) << r.out;
    EXPECT_GT(merged_in(path("s.json")), 40000);
  }
  const test::CliResult global = test::run_pss("render " + noisy + " -o " + path("o.png") +
                                               " --size 32x32 --support global --stats " + path("s.json"));
  ASSERT_EQ(global.exit_code, 0) << global.err;
  EXPECT_EQ(global.out.find("merged"), std::string::npos) << global.out;
  EXPECT_EQ(merged_in(path("s.json")), 0);
}

// Its points red or blue at random: a merged sample's colour is its points' mean, so the
// surface is an even purple. With each cube's first point's colour it came out in blotches
// of red and blue, tens of cubes to a support.
TEST_F(MergedSamplesCli, AMergedSamplesColourIsItsPointsMean) {
  test::SampleOptions o;
  o.count = 60000;
  o.noise = 0.06f;
  PointCloud cloud = test::sample(test::Torus{}, o);
  cloud.colors.resize(cloud.size());
  std::mt19937 rng(8);
  for (Rgb8& c : cloud.colors) c = rng() % 2 ? Rgb8{255, 0, 0} : Rgb8{0, 0, 255};
  write_ply(path("coloured.ply"), cloud);
  const test::CliResult r = test::run_pss("render " + path("coloured.ply") + " --color --transparent --size 48x48 -o " +
                                          path("o.exr") + " --stats " + path("s.json"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  ASSERT_GT(merged_in(path("s.json")), 40000);
  const test::ExrImage image = test::read_exr(path("o.exr"));
  std::vector<double> apart;  // per pixel hit: red and blue apart, a share of their sum
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const float red = image.at("R", x, y), blue = image.at("B", x, y);
      if (image.at("A", x, y) < 1 || !(red + blue > 0)) continue;
      apart.push_back(std::abs(double(red - blue)) / double(red + blue));
    }
  ASSERT_GT(apart.size(), 300u);
  std::sort(apart.begin(), apart.end());
  // Means: median 0.064, 90th percentile 0.19; first points' colours: 0.158 and 0.35.
  EXPECT_LT(apart[apart.size() / 2], 0.1);
  EXPECT_LT(apart[apart.size() * 9 / 10], 0.27);
}

// Tile by tile each tile merges the cubes of its samples whole, as in core (tiles/project.cpp):
// the same points merged, and the same surface to the rounding of sums taken in another order.
TEST_F(MergedSamplesCli, TileByTileACloudMergesAsInCore) {
  const test::ScratchFolder scratch(dir_ / "scratch");
  const test::CliResult core = test::run_pss("project " + path("noisy.ply") + " -o " + path("c.ply") + " --stats " +
                                             path("c.json"));
  ASSERT_EQ(core.exit_code, 0) << core.err;
  const test::CliResult tiled = test::run_pss("project " + path("noisy.ply") + " -o " + path("t.ply") +
                                              " --memory 8M --stats " + path("t.json"));
  ASSERT_EQ(tiled.exit_code, 0) << tiled.err;
  EXPECT_NE(tiled.out.find("tile by tile"), std::string::npos) << tiled.out;
  EXPECT_NE(tiled.out.find("points merged into samples"), std::string::npos) << tiled.out;
  EXPECT_GT(merged_in(path("t.json")), 40000);
  EXPECT_EQ(merged_in(path("t.json")), merged_in(path("c.json")));
  EXPECT_TRUE(scratch.empty());
  const PointCloud c = read_point_cloud(path("c.ply")), t = read_point_cloud(path("t.ply"));
  ASSERT_EQ(c.size(), t.size());
  std::ifstream in(path("c.json"));
  const float h = nlohmann::json::parse(in).at("params").at("h").get<float>();
  float farthest = 0;
  std::size_t beyond = 0, apart = 0;
  for (std::size_t i = 0; i < c.size(); ++i) {
    const float d = glm::length(c.positions[i] - t.positions[i]);
    farthest = std::max(farthest, d);
    beyond += d > 2e-3f * h;  // twice MLS's tolerance on t
    apart += glm::dot(c.normals[i], t.normals[i]) < 0;
  }
  // Rounding moves a point across MLS's stopping test, within its tolerance; one of the
  // 60,000 converges to another of two nearly equal minima of its energy, 3 tolerances away.
  EXPECT_LE(beyond, c.size() / 10000);
  EXPECT_LT(farthest, 1e-2f * h);
  EXPECT_EQ(apart, 0u);
}

}  // namespace
}  // namespace pss
