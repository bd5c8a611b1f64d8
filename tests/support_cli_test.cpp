// --support of `pss render` and `pss project` end to end (issue 26): adaptive by default, global
// when --h is given, either when named; recorded in --stats; and what it changes shows: on a
// sphere whose half is sampled 64 times sparser, one global h tears the sparse half.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "support/cli.hpp"
#include "support/output_readers.hpp"
#include "support/shapes.hpp"

namespace pss {
namespace {

using SupportCli = test::CliTest;

nlohmann::json read_json(const std::string& file) { return nlohmann::json::parse(std::ifstream(file)); }

// The sphere of render_test's SphereStep64 case, written as XYZ.
std::string stepped_sphere(const std::string& file) {
  test::SampleOptions o;
  o.count = 40000;
  o.step = 64;
  std::ofstream out(file);
  for (const vec3& p : test::sample(test::Sphere{}, o).positions) out << p.x << ' ' << p.y << ' ' << p.z << '\n';
  return file;
}

TEST_F(SupportCli, RenderIsAdaptiveByDefaultAndGlobalWithH) {
  const std::string cloud = stepped_sphere(path("step.xyz"));
  // The step runs down the middle of the picture: one side sparse, the other dense.
  const auto render = [&](const std::string& flags, const std::string& name) {
    const test::CliResult r = test::run_pss("render " + cloud + " --view 180,0 --size 64x64 -o " + path(name + ".png") +
                                            " --stats " + path(name + ".json") + flags);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return read_json(path(name + ".json"));
  };
  const nlohmann::json adaptive = render("", "default");
  const nlohmann::json global = render(" --support global", "global");
  const float h = adaptive["params"]["h"].get<float>();
  EXPECT_EQ(adaptive["params"]["support"], "adaptive");
  EXPECT_EQ(global["params"]["support"], "global");
  EXPECT_EQ(global["params"]["h"].get<float>(), h);
  EXPECT_EQ(global["params"]["h_largest"].get<float>(), h);
  EXPECT_GT(adaptive["params"]["h_largest"].get<float>(), 3 * h);
  EXPECT_GT(adaptive["params"]["support_levels"].get<int>(), 1);
  // Torn under one global h, whole with adaptive widths: the sphere covers ~1,000 pixels.
  const double hits_adaptive = adaptive["hits"].get<double>(), hits_global = global["hits"].get<double>();
  EXPECT_GT(hits_adaptive, 900);
  EXPECT_LT(hits_global, 0.8 * hits_adaptive) << hits_global;

  const std::string hh = " --h " + std::to_string(h);
  EXPECT_EQ(render(hh, "h")["params"]["support"], "global");
  EXPECT_EQ(render(hh + " --support adaptive", "h_adaptive")["params"]["support"], "adaptive");
}

// Projection: on the sparse half one global h leaves many points with too few neighbours
// (status 2, unmoved); adaptive widths project them.
TEST_F(SupportCli, ProjectIsAdaptiveByDefault) {
  const std::string cloud = stepped_sphere(path("step.xyz"));
  const auto too_few = [&](const std::string& flags, const std::string& name) {
    const test::CliResult r = test::run_pss("project " + cloud + " -o " + path(name + ".ply") + " --stats " +
                                            path(name + ".json") + flags);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(read_json(path(name + ".json"))["params"]["support"], name);
    const test::PlyColumns ply = test::read_ply_columns(path(name + ".ply"));
    int count = 0;
    for (double s : ply.columns.at("status")) count += s == 2;
    return count;
  };
  EXPECT_EQ(too_few("", "adaptive"), 0);
  EXPECT_GT(too_few(" --support global", "global"), 100);
}

TEST_F(SupportCli, AnUnknownSupportIsRefused) {
  const std::string cloud = write("c.xyz", "0 0 0\n1 0 0\n0 1 0\n1 1 0\n");
  expect_clean_failure("render " + cloud + " --support wide -o " + path("o.png"), "--support", path("o.png"));
  expect_clean_failure("project " + cloud + " --support wide -o " + path("o.ply"), "--support", path("o.ply"));
}

}  // namespace
}  // namespace pss
