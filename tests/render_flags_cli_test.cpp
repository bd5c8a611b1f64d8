// Flags of `pss render`, `pss project` and `pss volume` that change what is computed, end to end
// through the built pss: each is recorded as it took effect in --stats, and where its effect
// can be told from the outputs (--secondary, --ball-spacing, --iterations, --candidates, --reflectivity,
// project's --rho and --iterations) that effect must show.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "support/cli.hpp"
#include "support/output_readers.hpp"
#include "support/shapes.hpp"
#include "support/volumes.hpp"

namespace pss {
namespace {

void write_xyz(const std::string& file, const PointCloud& cloud) {
  std::ofstream out(file);
  for (const vec3& p : cloud.positions) out << p.x << ' ' << p.y << ' ' << p.z << '\n';
}

struct RenderFlags : test::CliTest {
  // Writes a unit sphere of 2000 samples; the render command of it at `size`, up to --stats's path.
  std::string sphere_render(const std::string& size) {
    test::SampleOptions o;
    o.count = 2000;
    write_xyz(path("sphere.xyz"), test::sample(test::Sphere{}, o));
    return "render " + path("sphere.xyz") + " --size " + size + " -o " + path("o.png") + " --stats ";
  }
};

// The scene of tests/secondary_test.cpp: a sphere of radius 0.5 hovering over a 3×3 plane.
PointCloud sphere_over_plane() {
  test::SampleOptions o;
  o.count = 3000;
  PointCloud cloud = test::sample(test::Sphere{vec3(0, 0, 1), 0.5f}, o);
  o.count = 8600;
  const PointCloud plane = test::sample_plane(1.5f, o);
  cloud.positions.insert(cloud.positions.end(), plane.positions.begin(), plane.positions.end());
  return cloud;
}

nlohmann::json read_json(const std::string& file) { return nlohmann::json::parse(std::ifstream(file)); }

// --secondary picks how reflection rays find the surface: the primary hits are the same in
// both modes, the mirror images differ (rough hits, tests/secondary_test.cpp), a little.
TEST_F(RenderFlags, SecondaryModeChangesOnlyWhatReflectionsShow) {
  write_xyz(path("scene.xyz"), sphere_over_plane());
  const std::string common = path("scene.xyz") + " --up 0,0,1 --view 0,40 --size 48x48 --reflections";
  for (const char* mode : {"full", "paper"}) {
    const std::string m = mode;
    const test::CliResult r = test::run_pss("render " + common + " --secondary " + m + " -o " + path(m + ".exr") +
                                            " --hits " + path(m + ".ply") + " --stats " + path(m + ".json"));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(read_json(path(m + ".json"))["params"]["secondary"], m);
  }
  EXPECT_EQ(read(path("full.ply")), read(path("paper.ply")));
  const test::ExrImage full = test::read_exr(path("full.exr")), paper = test::read_exr(path("paper.exr"));
  ASSERT_EQ(full.width, 48);
  ASSERT_EQ(paper.width, 48);
  int differ = 0, hits = 0;
  double largest = 0;
  for (int y = 0; y < full.height; ++y)
    for (int x = 0; x < full.width; ++x) {
      const bool hit = std::isfinite(full.at("Z", x, y));
      hits += hit;
      double d = 0;
      for (const char* c : {"R", "G", "B"})
        d = std::max(d, double(std::abs(full.at(c, x, y) - paper.at(c, x, y))));
      if (d == 0) continue;
      ++differ;
      EXPECT_TRUE(hit) << x << ',' << y;  // the background reflects nothing
      largest = std::max(largest, d);
    }
  EXPECT_GT(hits, 300);
  EXPECT_GT(differ, 20);
  EXPECT_LT(largest, 0.05);
}

// The MLS parameters of `pss render` reach the preparation and the search, as --stats records
// them: --iterations caps the projections per candidate; --ball-spacing 0 keeps one local
// polynomial per sample that has neighbours (as the paper), the default b/2 far fewer.
TEST_F(RenderFlags, SurfaceParametersTakeEffect) {
  const std::string common = sphere_render("24x24");
  ASSERT_EQ(test::run_pss(common + path("default.json")).exit_code, 0);
  const test::CliResult r = test::run_pss(common + path("set.json") +
                                          " --h 0.1 --rho 0.25 --b 0.12 --ball-spacing 0 --epsilon 2e-5"
                                          " --iterations 1 --shadows --reflections --reflectivity 0.4");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json set = read_json(path("set.json")), defaults = read_json(path("default.json"));
  EXPECT_FLOAT_EQ(set["params"]["h"].get<float>(), 0.1f);
  EXPECT_FLOAT_EQ(set["params"]["rho"].get<float>(), 0.25f);
  EXPECT_FLOAT_EQ(set["params"]["b"].get<float>(), 0.12f);
  EXPECT_EQ(set["params"]["ball_spacing"].get<float>(), 0.0f);
  EXPECT_FLOAT_EQ(set["params"]["epsilon"].get<float>(), 2e-5f);
  EXPECT_EQ(set["params"]["iterations"], "1");
  // One projection per candidate, where the default 2 is nearly always reached (capped).
  EXPECT_LT(set["mean_iterations"].get<double>(), 1.5);
  EXPECT_GT(defaults["mean_iterations"].get<double>(), 1.5);
  EXPECT_EQ(set["shading"]["shadows"], true);
  EXPECT_EQ(set["shading"]["reflections"], true);
  EXPECT_FLOAT_EQ(set["shading"]["reflectivity"].get<float>(), 0.4f);
  EXPECT_GT(set["secondary_rays"].get<std::int64_t>(), set["hits"].get<std::int64_t>());
  EXPECT_EQ(set["local_polynomials"].get<std::int64_t>() + set["samples_left_out"].get<std::int64_t>(), 2000);
  // The defaults: b = h, δ = b/2, ε = 1e-3·h, ρ = 2h, no secondary rays.
  const float h = defaults["params"]["h"].get<float>();
  EXPECT_FLOAT_EQ(defaults["params"]["b"].get<float>(), h);
  EXPECT_FLOAT_EQ(defaults["params"]["ball_spacing"].get<float>(), 0.5f * h);
  EXPECT_FLOAT_EQ(defaults["params"]["rho"].get<float>(), 2 * h);
  EXPECT_EQ(defaults["secondary_rays"].get<std::int64_t>(), 0);
  EXPECT_LT(defaults["local_polynomials"].get<std::int64_t>(), 1000);
}

// A ball wider than the support: the polynomials' far reaches made hits up to 5 units off a
// unit sphere (--b 10), every one a capped candidate. Refused, naming b and rho; b = rho renders.
TEST_F(RenderFlags, ABallWiderThanTheSupportIsRefused) {
  const std::string common = sphere_render("16x16");
  const test::CliResult wide = test::run_pss(common + path("wide.json") + " --h 0.1 --b 0.21");
  EXPECT_NE(wide.exit_code, 0);
  EXPECT_FALSE(std::filesystem::exists(path("o.png")));
  EXPECT_NE(wide.err.find("the ball radius b = 0.21 is larger than rho = 0.2"), std::string::npos) << wide.err;
  EXPECT_EQ(test::line_count(wide.err), 1) << wide.err;
  EXPECT_EQ(test::run_pss(common + path("edge.json") + " --h 0.1 --b 0.2").exit_code, 0);
  EXPECT_TRUE(std::filesystem::exists(path("o.png")));
}

// --candidates caps the ball intersections a ray tries: with one, the rays whose first
// candidate is rejected (those that graze the sphere's silhouette) end as misses.
TEST_F(RenderFlags, CandidatesCapTheBallsARayTries) {
  const std::string common = sphere_render("48x48");
  ASSERT_EQ(test::run_pss(common + path("default.json")).exit_code, 0);
  const test::CliResult r = test::run_pss(common + path("one.json") + " --candidates 1");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json one = read_json(path("one.json")), defaults = read_json(path("default.json"));
  EXPECT_EQ(one["params"]["max_candidates"], 1);
  EXPECT_EQ(defaults["params"]["max_candidates"], 32);
  EXPECT_LT(one["hits"].get<std::int64_t>(), defaults["hits"].get<std::int64_t>());
  EXPECT_GT(one["hits"].get<std::int64_t>(), defaults["hits"].get<std::int64_t>() * 9 / 10);
}

// --borders (points/borders.hpp): auto clips a mesh's vertices (an OFF file with faces) and
// extends a scan (the same points as XYZ); clip and extend force either. An open square's
// surface runs on past its samples only where extended: more hits, none of them clipped
// ones; a value that is no mode is refused, naming the flag.
TEST_F(RenderFlags, BordersClipAMeshsVerticesAndExtendAScan) {
  test::SampleOptions o;
  o.count = 3000;
  const PointCloud square = test::sample_plane(1.0f, o);
  write_xyz(path("square.xyz"), square);
  {
    std::ofstream off(path("square.off"));
    off << "OFF\n" << square.size() << " 1 0\n";
    for (const vec3& p : square.positions) off << p.x << ' ' << p.y << ' ' << p.z << '\n';
    off << "3 0 1 2\n";
  }
  const auto render = [&](const std::string& file, const std::string& flags, const std::string& name) {
    const test::CliResult r = test::run_pss("render " + path(file) + " --up 0,0,1 --view 20,50 --size 64x64 -o " +
                                            path(name + ".png") + " --stats " + path(name + ".json") + flags);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return read_json(path(name + ".json"));
  };
  const nlohmann::json mesh = render("square.off", "", "mesh"), scan = render("square.xyz", "", "scan");
  EXPECT_EQ(mesh["params"]["borders"], "clip");
  EXPECT_EQ(scan["params"]["borders"], "extend");
  const auto hits = [](const nlohmann::json& j) { return j["hits"].get<std::int64_t>(); };
  EXPECT_GT(hits(scan), hits(mesh) + 30);
  const nlohmann::json mesh_extended = render("square.off", " --borders extend", "mesh_extended");
  const nlohmann::json scan_clipped = render("square.xyz", " --borders clip", "scan_clipped");
  EXPECT_EQ(mesh_extended["params"]["borders"], "extend");
  EXPECT_EQ(scan_clipped["params"]["borders"], "clip");
  EXPECT_EQ(hits(mesh_extended), hits(scan));
  EXPECT_EQ(hits(scan_clipped), hits(mesh));
  const test::CliResult bad = test::run_pss("render " + path("square.xyz") + " -o " + path("bad.png") + " --borders trim");
  EXPECT_NE(bad.exit_code, 0);
  EXPECT_NE(bad.err.find("--borders"), std::string::npos) << bad.err;
  EXPECT_FALSE(std::filesystem::exists(path("bad.png")));
}

using ProjectFlags = test::CliTest;

// Where the noise sets h, APSS's and RIMLS's fits converge slowly: the default cap of 8
// brings a noisy sphere's projections home, where 4 left a sixth of them moving.
TEST_F(ProjectFlags, ApssAndRimlsConvergeOnANoisyCloudByDefault) {
  test::SampleOptions o;
  o.count = 20000;
  o.noise = 0.02f;
  write_xyz(path("noisy.xyz"), test::sample(test::Sphere{}, o));
  for (const char* surface : {"apss", "rimls"}) {
    SCOPED_TRACE(surface);
    const auto statuses = [&](const std::string& flags) {
      const test::CliResult r = test::run_pss("project " + path("noisy.xyz") + " -o " + path("p.xyz") + " --surface " +
                                              surface + " --stats " + path("s.json") + flags);
      EXPECT_EQ(r.exit_code, 0) << r.err;
      return read_json(path("s.json"));
    };
    const nlohmann::json defaults = statuses("");
    EXPECT_EQ(defaults["params"]["max_mls_iterations"], 8);
    EXPECT_LT(defaults["status"]["not_converged"].get<int>(), 20);
    EXPECT_GT(statuses(" --iterations 4")["status"]["not_converged"].get<int>(), 1000);
  }
}

// --rho below the samples' spacing leaves every point without the 3 neighbours a plane
// needs; with MLS, --iterations 1 leaves some of a noisy sphere's points short of
// convergence that the default 4 brings home (RIMLS's one step lands within its tolerance).
TEST_F(ProjectFlags, RhoAndIterationsTakeEffect) {
  test::SampleOptions o;
  o.count = 2000;
  o.noise = 0.005f;
  write_xyz(path("sphere.xyz"), test::sample(test::Sphere{}, o));
  const auto project = [&](const std::string& flags, const std::string& name) {
    const test::CliResult r =
        test::run_pss("project " + path("sphere.xyz") + " -o " + path("p.xyz") + " --surface mls --stats " + path(name) +
                      flags);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return read_json(path(name));
  };
  const nlohmann::json defaults = project("", "default.json");
  EXPECT_EQ(defaults["status"]["converged"], 2000);
  EXPECT_EQ(defaults["params"]["max_mls_iterations"], 4);  // MLS's default (APSS's and RIMLS's: 8)
  const nlohmann::json one = project(" --iterations 1", "one.json");
  EXPECT_EQ(one["params"]["max_mls_iterations"], 1);
  EXPECT_GT(one["status"]["not_converged"].get<int>(), 100);
  EXPECT_FLOAT_EQ(project(" --rho 0.3", "rho.json")["params"]["rho"].get<float>(), 0.3f);
  // 2000 samples on the unit sphere lie 0.04 from their nearest neighbour on average: within
  // 0.01 no point has a neighbour, and nothing can be projected.
  const test::CliResult tiny = test::run_pss("project " + path("sphere.xyz") + " -o " + path("p.xyz") + " --rho 0.01");
  EXPECT_NE(tiny.exit_code, 0);
  EXPECT_NE(tiny.err.find("rho = 0.01 (too few neighbours 2000"), std::string::npos) << tiny.err;
}

using VolumeFlags = test::CliTest;

// The projection's parameters of `pss volume`, in voxels (u = 1 here), reach the prepared
// volume as --stats records it: h, b = k·h, the neighbourhood radius in h, α1, ε and θ1's k.
TEST_F(VolumeFlags, ProjectionParametersTakeEffect) {
  write("ball.raw", test::uint8_raw_bytes(test::sphere_distance(vec3(32.0f), 10.0f), ivec3(64)));
  const test::CliResult r = test::run_pss("volume " + path("ball.raw") + " --dims 64x64x64 --type uint8 --iso 100"
                                          " --size 16x16 -o " + path("v.png") + " --stats " + path("v.json") +
                                          " --h 2.5 --k 0.6 --radius 1.6 --alpha 0.5 --error 0.2 --smoothing 2");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json v = read_json(path("v.json"))["volume"];
  EXPECT_FLOAT_EQ(v["params"]["h"].get<float>(), 2.5f);
  EXPECT_FLOAT_EQ(v["params"]["b"].get<float>(), 1.5f);
  EXPECT_FLOAT_EQ(v["params"]["radius"].get<float>(), 4.0f);
  EXPECT_FLOAT_EQ(v["params"]["alpha"].get<float>(), 0.5f);
  EXPECT_FLOAT_EQ(v["params"]["epsilon"].get<float>(), 0.2f);
  EXPECT_FLOAT_EQ(v["feature"]["smoothing"].get<float>(), 2.0f);
}

}  // namespace
}  // namespace pss
