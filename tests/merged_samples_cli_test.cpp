// The merged samples from the command line (points/merged_samples.hpp, issue 26): pss info,
// project, render and mesh say how many points were merged, in their summaries and --stats;
// --support global merges none; tile by tile a cloud that merges is refused in one line.
#include <gtest/gtest.h>

#include <fstream>

#include <nlohmann/json.hpp>

#include "pss/io/ply.hpp"
#include "support/cli.hpp"
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

TEST_F(MergedSamplesCli, TileByTileACloudThatMergesIsRefusedInOneLine) {
  const test::ScratchFolder scratch(dir_ / "scratch");
  const test::CliResult r = test::run_pss("project " + path("noisy.ply") + " -o " + path("o.ply") + " --memory 6M");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(test::line_count(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("tile by tile"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("merge"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(path("o.ply")));
  EXPECT_TRUE(scratch.empty());
}

}  // namespace
}  // namespace pss
