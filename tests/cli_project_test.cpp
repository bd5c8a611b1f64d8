// `pss info` and `pss project` as a user runs them: outputs that other tools can read, and
// for every bad input one line naming the file and the problem, a non-zero exit, no output.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>

#include "pss/io/ply.hpp"
#include "pss/points/spacing.hpp"
#include "pss/points/support.hpp"
#include "support/cli.hpp"
#include "support/shapes.hpp"

namespace pss {
namespace {

namespace fs = std::filesystem;

class CliProject : public test::CliTest {};

const std::string kHeader = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nend_header\n";

TEST_F(CliProject, ProjectsASphereAndWritesAReadablePly) {
  test::SampleOptions o;
  o.noise = 0.005f;
  write_ply(path("sphere.ply"), test::sample(test::Sphere{}, o));
  const test::CliResult r = test::run_pss("project " + path("sphere.ply") + " -o " + path("out.ply") +
                                          " --backend cpu --stats " + path("stats.json"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("wrote " + path("out.ply")), std::string::npos);
  const PointCloud out = read_ply(path("out.ply"));
  ASSERT_EQ(out.size(), 4000u);
  ASSERT_TRUE(out.has_normals());
  for (std::size_t i = 0; i < out.size(); ++i) {
    EXPECT_NEAR(glm::length(out.positions[i]), 1.0f, 0.01f);  // 2σ of the input noise
    EXPECT_GT(glm::dot(out.normals[i], glm::normalize(out.positions[i])), 0.98f);
  }
  std::ifstream stats(path("stats.json"));
  std::string json((std::istreambuf_iterator<char>(stats)), {});
  EXPECT_NE(json.find("\"projection\""), std::string::npos);
  EXPECT_NE(json.find("\"points\": 4000"), std::string::npos);
}

// The input's scalar properties come out in their types, each value beside its own point's
// projection; the input's own 'status' is kept, as input_status, beside the projection's.
TEST_F(CliProject, PassesTheInputsScalarsThroughInItsOrder) {
  PointCloud in = test::sample(test::Sphere{}, {});
  ScalarProperty label{"label", ScalarType::uint8, {}}, intensity{"intensity", ScalarType::float32, {}},
      status{"status", ScalarType::int32, {}};
  for (std::size_t i = 0; i < in.size(); ++i) {
    label.values.push_back(double(i % 256));
    intensity.values.push_back(0.25 * double(i));
    status.values.push_back(-double(i));
  }
  in.scalars = {label, intensity, status};
  write_ply(path("in.ply"), in);
  const test::CliResult r = test::run_pss("project " + path("in.ply") + " -o " + path("out.ply") + " --backend cpu");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const PointCloud out = read_ply(path("out.ply"));
  ASSERT_EQ(out.size(), in.size());
  ASSERT_EQ(out.scalars.size(), 4u);
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(out.scalars[k].name, in.scalars[k].name == "status" ? "input_status" : in.scalars[k].name);
    EXPECT_EQ(out.scalars[k].type, in.scalars[k].type) << out.scalars[k].name;
    EXPECT_EQ(out.scalars[k].values, in.scalars[k].values) << out.scalars[k].name;
  }
  EXPECT_EQ(out.scalars[3].name, "status");
  EXPECT_EQ(out.scalars[3].type, ScalarType::int32);
  for (std::size_t i = 0; i < out.size(); ++i) {
    // Samples lie on the sphere: each projection stays at its own point, about 0.06 from the next.
    EXPECT_LT(glm::distance(out.positions[i], in.positions[i]), 0.005f) << i;
    EXPECT_TRUE(out.scalars[3].values[i] >= 0 && out.scalars[3].values[i] <= 3) << i;
  }
}

TEST_F(CliProject, InfoReportsSizeAndSuggestedH) {
  write_ply(path("sphere.ply"), test::sample(test::Sphere{}, {}));
  const test::CliResult r = test::run_pss("info " + path("sphere.ply"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("points          4000"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("suggested h"), std::string::npos);
}

// The spread of the spacing, as the library estimates it for the cloud as written: a sphere
// whose upper half is sampled 8 times more densely.
TEST_F(CliProject, InfoReportsTheSpreadOfTheSpacing) {
  PointCloud cloud;
  for (const vec3& p : test::sample(test::Sphere{}, {}).positions)
    if (p.y < 0) cloud.positions.push_back(p);
  test::SampleOptions dense;
  dense.count = 32000;
  for (const vec3& p : test::sample(test::Sphere{}, dense).positions)
    if (p.y >= 0) cloud.positions.push_back(p);
  write_ply(path("uneven.ply"), cloud);
  const test::CliResult r = test::run_pss("info " + path("uneven.ply"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::size_t at = r.out.find("15th neighbour  min ");
  ASSERT_NE(at, std::string::npos) << r.out;
  double least = 0, median = 0, largest = 0, ratio = 0;
  ASSERT_EQ(std::sscanf(r.out.c_str() + at, "15th neighbour  min %lf, median %lf, max %lf (max/min %lf)", &least, &median,
                        &largest, &ratio),
            4)
      << r.out;
  const SpacingEstimate e = estimate_spacing(read_ply(path("uneven.ply")).positions);
  EXPECT_NEAR(least, e.min_kth, 1e-5 * e.min_kth);
  EXPECT_NEAR(median, e.median_kth, 1e-5 * e.median_kth);
  EXPECT_NEAR(largest, e.max_kth, 1e-5 * e.max_kth);
  EXPECT_NEAR(ratio, e.max_kth / e.min_kth, 1e-2 * ratio);
  EXPECT_GT(ratio, 2.0);  // √8 between the halves' spacings
  // The adaptive widths render and project use: those of support_widths, h to wider.
  const std::size_t w = r.out.find("adaptive h_i    from ");
  ASSERT_NE(w, std::string::npos) << r.out;
  double narrowest = 0, widest = 0;
  ASSERT_EQ(std::sscanf(r.out.c_str() + w, "adaptive h_i    from %lf to %lf", &narrowest, &widest), 2) << r.out;
  ProjectionParams params = ProjectionParams::from_h(float(e.suggested_h));
  params.support = Support::adaptive;
  const SupportWidths widths = support_widths(read_ply(path("uneven.ply")).positions, params);
  EXPECT_NEAR(narrowest, widths.least, 1e-5 * widths.least);
  EXPECT_NEAR(widest, widths.largest, 1e-5 * widths.largest);
  EXPECT_GT(widest, 1.5 * narrowest);
}

// A cloud whose noise is over a third of its spacing's h: pss info reports the noise and the
// h it sets, and pss mesh uses that h without --h.
TEST_F(CliProject, InfoReportsTheNoiseAndTheHItSets) {
  test::SampleOptions o;
  o.count = 8000;
  o.noise = 0.06f;
  write_ply(path("noisy.ply"), test::sample(test::Sphere{}, o));
  const SpacingEstimate e = estimate_spacing(read_ply(path("noisy.ply")).positions);
  ASSERT_GT(e.suggested_h, e.median_kth);
  const test::CliResult r = test::run_pss("info " + path("noisy.ply"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  double h = 0, noise = 0;
  const std::size_t at = r.out.find("suggested h     "), n = r.out.find("noise           ");
  ASSERT_TRUE(at != std::string::npos && n != std::string::npos) << r.out;
  ASSERT_EQ(std::sscanf(r.out.c_str() + at, "suggested h     %lf", &h), 1);
  ASSERT_EQ(std::sscanf(r.out.c_str() + n, "noise           %lf", &noise), 1);
  EXPECT_NEAR(h, e.suggested_h, 1e-5 * h);
  EXPECT_NEAR(noise, e.noise, 1e-5 * noise);
  EXPECT_NEAR(noise, 0.06, 0.006);
  EXPECT_NE(r.out.find("3 times the noise"), std::string::npos) << r.out;
  const test::CliResult m = test::run_pss("mesh " + path("noisy.ply") + " -o " + path("noisy_mesh.ply"));
  ASSERT_EQ(m.exit_code, 0) << m.err;
  const std::size_t used = m.out.find(", h = ");
  ASSERT_NE(used, std::string::npos) << m.out;
  EXPECT_NEAR(std::stod(m.out.substr(used + 6)), e.suggested_h, 1e-5 * h);
  EXPECT_NE(m.out.find("1 component, watertight"), std::string::npos) << m.out;
}

// The bounds carry the file's digits, not a float's binary expansion (-0.09468989819).
TEST_F(CliProject, InfoPrintsTheBoundsWithTheFilesDigits) {
  write("b.xyz", "-0.0946899 0.0329874 -0.0618736\n0.0610091 0.187321 0.0587997\n1e-3 0.1 0\n");
  const test::CliResult r = test::run_pss("info " + path("b.xyz"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("bounds          [-0.0946899, 0.0610091] x [0.0329874, 0.187321] x [-0.0618736, 0.0587997]\n"),
            std::string::npos)
      << r.out;
}

// A bound that rounds to a whole number reads as one (-100, not -1e+02), and a cloud of four
// points names its 3rd nearest neighbour (not "3th").
TEST_F(CliProject, InfoPrintsWholeBoundsAndOrdinalsAsWritten) {
  write("c.xyz", "-99.9999999 0 0\n1 2 3\n0 1 0\n1 1 0.5\n");
  const test::CliResult r = test::run_pss("info " + path("c.xyz"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("bounds          [-100, 1] x "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("the 3rd nearest neighbour"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("3rd neighbour   min "), std::string::npos) << r.out;
  // Its suggested h is refused by project, render and mesh: info says so.
  EXPECT_NE(r.out.find("too few points  rho = 2h spans the whole cloud"), std::string::npos) << r.out;
  std::string grid;  // 400 points: h about a spacing, far inside the cloud
  for (int i = 0; i < 20; ++i)
    for (int j = 0; j < 20; ++j) grid += std::to_string(0.05 * i) + " " + std::to_string(0.05 * j) + " 0\n";
  write("grid.xyz", grid);
  const test::CliResult ok = test::run_pss("info " + path("grid.xyz"));
  ASSERT_EQ(ok.exit_code, 0) << ok.err;
  EXPECT_EQ(ok.out.find("too few points"), std::string::npos) << ok.out;
}

TEST_F(CliProject, MissingFile) {
  expect_clean_failure("project " + path("nope.ply") + " -o " + path("out.ply"), path("nope.ply"), path("out.ply"));
  expect_clean_failure("info " + path("nope.ply"), path("nope.ply"), path("out.ply"));
}

TEST_F(CliProject, MalformedAndTruncatedPly) {
  const std::string garbage = write("garbage.ply", "this is not a ply file\n");
  expect_clean_failure("project " + garbage + " -o " + path("out.ply"), garbage, path("out.ply"));
  const std::string truncated = write("truncated.ply", kHeader + "0 0 0\n1 1 1\n");
  expect_clean_failure("project " + truncated + " -o " + path("out.ply"), "truncated", path("out.ply"));
}

TEST_F(CliProject, NonFiniteCoordinates) {
  const std::string nan = write("nan.ply", kHeader + "0 0 0\nnan 1 1\n2 2 2\n");
  expect_clean_failure("project " + nan + " -o " + path("out.ply"), "non-finite", path("out.ply"));
  const std::string inf = write("inf.xyz", "0 0 0\n1 inf 1\n");
  expect_clean_failure("project " + inf + " -o " + path("out.ply"), "non-finite", path("out.ply"));
}

TEST_F(CliProject, EmptyCloud) {
  const std::string empty = write("empty.ply", "ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\n"
                                               "property float y\nproperty float z\nend_header\n");
  expect_clean_failure("project " + empty + " -o " + path("out.ply"), empty, path("out.ply"));
}

// Points that all coincide define no surface, even with --h (which the spacing's estimate
// cannot give them): every projection "converged" with a made-up normal, and render drew a
// disc. A cluster of coincident points beside one far point spans no plane either: its fits
// have no normal (a zero covariance), so nothing is projected.
TEST_F(CliProject, CoincidentPointsDefineNoSurface) {
  std::string same, cluster;
  for (int i = 0; i < 100; ++i) same += "0.5 0.25 -1\n";
  cluster = same + "5 5 5\n";
  write("same.xyz", same);
  write("cluster.xyz", cluster);
  for (const char* command : {"project", "render"}) {
    const std::string out = path(std::string("out.") + (command == std::string("render") ? "png" : "ply"));
    expect_clean_failure(std::string(command) + " " + path("same.xyz") + " --h 0.1 -o " + out,
                         "the points all coincide", out);
  }
  expect_clean_failure("project " + path("cluster.xyz") + " --h 0.1 -o " + path("out.ply"),
                       "lie on a line or coincide", path("out.ply"));
}

TEST_F(CliProject, AbsurdParameters) {
  write_ply(path("sphere.ply"), test::sample(test::Sphere{}, {}));
  const std::string in = path("sphere.ply"), out = path("out.ply");
  expect_clean_failure("project " + in + " -o " + out + " --h 0", "--h", out);
  expect_clean_failure("project " + in + " -o " + out + " --h -1", "--h", out);
  expect_clean_failure("project " + in + " -o " + out + " --h nan", "--h", out);
  expect_clean_failure("project " + in + " -o " + out + " --backend quantum", "--backend", out);
  expect_clean_failure("project " + in + " -o " + out + " --bogus", "--bogus", out);
}

TEST_F(CliProject, CudaWithoutADeviceIsAClearError) {
  write_ply(path("sphere.ply"), test::sample(test::Sphere{}, {}));
  // This machine has no GPU in CI: the build either lacks CUDA or finds no device.
  const test::CliResult probe = test::run_pss("project " + path("sphere.ply") + " -o " + path("out.ply") +
                                              " --backend cuda");
  if (probe.exit_code == 0) GTEST_SKIP() << "a CUDA device is present";
  fs::remove(path("out.ply"));
  expect_clean_failure("project " + path("sphere.ply") + " -o " + path("out.ply") + " --backend cuda", "cuda",
                       path("out.ply"));
}

TEST_F(CliProject, UnwritableOutput) {
  write_ply(path("sphere.ply"), test::sample(test::Sphere{}, {}));
  const std::string out = path("no-such-dir/out.ply");
  expect_clean_failure("project " + path("sphere.ply") + " -o " + out, out, out);
}

}  // namespace
}  // namespace pss
