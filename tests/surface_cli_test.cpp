// --surface, --normals and --outliers of `pss project` and `pss render` end to end (issue 26): MLS by
// default; APSS reproduces a sphere sampled with its exact normals to rounding, which MLS
// cannot; the normals' source is the file's unless --normals estimate, and both are named
// in the summary and --stats; bad values are refused.
#include <gtest/gtest.h>

#include <cstdio>

#include <cmath>
#include <fstream>
#include <random>
#include <string>
#include <utility>

#include <nlohmann/json.hpp>

#include "support/cli.hpp"
#include "support/output_readers.hpp"
#include "support/shapes.hpp"

namespace pss {
namespace {

using SurfaceCli = test::CliTest;

nlohmann::json read_json(const std::string& file) { return nlohmann::json::parse(std::ifstream(file)); }

// A unit sphere as XYZ, with its exact normals (six columns), wrong ones (tilted toward +x by
// up to 30°: they still follow the points), ones that do not follow the points (+x
// everywhere: "one way"), exact ones flipped on the half x > 0, or some zero (about its pole
// z > 0.9; the others any: (x, 0, z)).
std::string sphere(const std::string& file, const char* normals) {
  test::SampleOptions o;
  o.count = 6000;
  std::ofstream out(file);
  out.precision(9);
  for (const vec3& p : test::sample(test::Sphere{}, o).positions) {
    out << p.x << ' ' << p.y << ' ' << p.z;
    if (normals == std::string("exact")) out << ' ' << p.x << ' ' << p.y << ' ' << p.z;
    if (normals == std::string("wrong")) out << ' ' << p.x + 0.5f << ' ' << p.y << ' ' << p.z;
    if (normals == std::string("one way")) out << " 1 0 0";
    if (normals == std::string("some zero")) out << ' ' << (p.z > 0.9f ? 0.0f : p.x) << " 0 " << (p.z > 0.9f ? 0.0f : p.z);
    if (normals == std::string("some nan")) out << ' ' << (p.z > 0.9f ? "nan" : std::to_string(p.x)) << " 0 " << p.z;
    if (normals == std::string("flipped")) {
      const float sign = p.x > 0 ? -1.0f : 1.0f;
      out << ' ' << sign * p.x << ' ' << sign * p.y << ' ' << sign * p.z;
    }
    out << '\n';
  }
  return file;
}

double worst_radius_error(const std::string& ply) {
  const test::PlyColumns c = test::read_ply_columns(ply);
  double worst = 0;
  for (std::size_t i = 0; i < c.columns.at("x").size(); ++i)
    worst = std::max(worst, std::abs(std::hypot(c.columns.at("x")[i], c.columns.at("y")[i], c.columns.at("z")[i]) - 1));
  return worst;
}

TEST_F(SurfaceCli, ProjectFitsTheChosenSurfaceWithTheChosenNormals) {
  const std::string exact = sphere(path("exact.xyz"), "exact"), wrong = sphere(path("wrong.xyz"), "wrong");
  const auto project = [&](const std::string& cloud, const std::string& flags, const std::string& name) {
    const test::CliResult r =
        test::run_pss("project " + cloud + " -o " + path(name + ".ply") + " --stats " + path(name + ".json") + flags);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return r.out;
  };
  EXPECT_NE(project(exact, " --surface mls", "mls").find("mls surface, h ="), std::string::npos);
  EXPECT_EQ(read_json(path("mls.json"))["params"]["surface"], "mls");
  EXPECT_EQ(read_json(path("mls.json"))["params"]["normals"], "none");
  EXPECT_NE(project(exact, " --surface apss", "apss").find("apss surface (the file's normals)"), std::string::npos);
  EXPECT_EQ(read_json(path("apss.json"))["params"]["surface"], "apss");
  EXPECT_EQ(read_json(path("apss.json"))["params"]["normals"], "file");
  const double mls_error = worst_radius_error(path("mls.ply")), apss_error = worst_radius_error(path("apss.ply"));
  EXPECT_LT(apss_error, 2e-6);
  EXPECT_GT(mls_error, 10 * apss_error);
  // The file's wrong normals bend APSS's spheres; estimated ones do not.
  project(wrong, " --surface apss", "wrong_file");
  EXPECT_NE(project(wrong, " --surface apss --normals estimate", "wrong_estimated").find("(estimated normals)"),
            std::string::npos);
  EXPECT_EQ(read_json(path("wrong_estimated.json"))["params"]["normals"], "estimated");
  EXPECT_GT(worst_radius_error(path("wrong_file.ply")), 0.01);
  EXPECT_LT(worst_radius_error(path("wrong_estimated.ply")), 10 * mls_error);
  project(exact, " --surface rimls", "rimls");
  EXPECT_EQ(read_json(path("rimls.json"))["params"]["surface"], "rimls");
}

// A file whose normals are flipped on half the sphere: `project` and `render` turn that half
// (points/turn_flipped_normals.hpp), say so and count it, and APSS fits the sphere as with the
// exact normals; a file that agrees, or normals not taken from the file, turn none.
TEST_F(SurfaceCli, AFlippedHalfOfTheFilesNormalsIsTurned) {
  const std::string exact = sphere(path("exact.xyz"), "exact"), flipped = sphere(path("flipped.xyz"), "flipped");
  std::size_t half = 0;
  {
    std::ifstream in(flipped);
    float x, y, z, nx, ny, nz;
    std::size_t positive = 0, all = 0;
    while (in >> x >> y >> z >> nx >> ny >> nz) positive += x > 0, ++all;
    half = std::min(positive, all - positive);
  }
  ASSERT_GT(half, 2500u);
  const auto run = [&](const std::string& command, const std::string& cloud, const std::string& flags,
                       const std::string& name, const char* extension) {
    const test::CliResult r = test::run_pss(command + " " + cloud + " -o " + path(name + extension) + " --stats " +
                                            path(name + ".json") + flags);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return r.out;
  };
  const std::string turned = run("project", flipped, " --surface apss", "flipped", ".ply");
  EXPECT_NE(turned.find("turned " + std::to_string(half) + " of the file's normals (of 6000 points)"), std::string::npos)
      << turned;
  EXPECT_EQ(read_json(path("flipped.json"))["normals_turned"], half);
  EXPECT_LT(worst_radius_error(path("flipped.ply")), 2e-6);
  EXPECT_EQ(run("project", exact, " --surface apss", "exact", ".ply").find("turned"), std::string::npos);
  EXPECT_EQ(read_json(path("exact.json"))["normals_turned"], 0);
  EXPECT_EQ(run("project", flipped, " --surface apss --normals estimate", "estimated", ".ply").find("turned"),
            std::string::npos);
  EXPECT_EQ(read_json(path("estimated.json"))["normals_turned"], 0);
  EXPECT_NE(run("render", flipped, " --surface rimls --size 48x48", "render", ".png").find("turned"), std::string::npos);
  EXPECT_EQ(read_json(path("render.json"))["normals_turned"], half);
}

// `pss info` says whether a file's normals agree, as render and project would find.
TEST_F(SurfaceCli, InfoSaysWhetherTheFilesNormalsAgree) {
  const auto info = [&](const std::string& file) {
    const test::CliResult r = test::run_pss("info " + file);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    const std::size_t at = r.out.find("normals         ");
    return at == std::string::npos ? std::string() : r.out.substr(at, r.out.find('\n', at) - at);
  };
  EXPECT_EQ(info(sphere(path("exact.xyz"), "exact")), "normals         the file's follow the points and face one way");
  const std::string flipped = sphere(path("flipped.xyz"), "flipped");
  const test::CliResult projected = test::run_pss("project " + flipped + " -o " + path("p.ply") + " --stats " +
                                                  path("p.json"));
  ASSERT_EQ(projected.exit_code, 0) << projected.err;
  const int turned = read_json(path("p.json"))["normals_turned"];
  ASSERT_GT(turned, 2500);
  EXPECT_EQ(info(flipped), "normals         the file's: render and project turn " + std::to_string(turned) +
                               " of 6000 (a part faced inward, or was flipped against the rest)");
  const std::string one_way = info(sphere(path("one_way.xyz"), "one way"));
  unsigned long long off = 0;
  ASSERT_EQ(std::sscanf(one_way.c_str(), "normals         the file's: those of %llu of 6000 samples lie more than 45 "
                                         "degrees off their neighbours' plane", &off), 1) << one_way;
  EXPECT_NEAR(double(off), 0.707 * 6000, 200);  // where |x| < cos 45°
  // With strays about the sphere, whose normals point anywhere: info counts as render, which
  // sets them aside before the turn.
  {
    std::ofstream out(path("strays.xyz"), std::ios::app);
    out << std::ifstream(flipped).rdbuf();
    std::mt19937 rng(4);
    std::uniform_real_distribution<float> u(-1.5f, 1.5f);
    for (int i = 0; i < 40;) {
      const vec3 p(u(rng), u(rng), u(rng));
      if (std::abs(glm::length(p) - 1) < 0.15f) continue;
      out << p.x << ' ' << p.y << ' ' << p.z << ' ' << (i % 2 ? 1 : -1) << " 0 0\n";
      ++i;
    }
  }
  const test::CliResult rendered = test::run_pss("render " + path("strays.xyz") + " --size 32x32 -o " + path("s.png") +
                                                 " --stats " + path("s.json"));
  ASSERT_EQ(rendered.exit_code, 0) << rendered.err;
  ASSERT_GT(read_json(path("s.json"))["outliers_set_aside"].get<int>(), 20);
  EXPECT_EQ(info(path("strays.xyz")), "normals         the file's: render and project turn " +
                                          std::to_string(read_json(path("s.json"))["normals_turned"].get<int>()) +
                                          " of 6040 (a part faced inward, or was flipped against the rest)");
  std::ofstream(path("zero.xyz")) << "0 0 0 0 0 1\n1 0 0 0 0 0\n0 1 0 0 0 1\n1 1 0 0 0 1\n0.5 0.5 0.1 0 0 1\n";
  EXPECT_EQ(info(path("zero.xyz")), "normals         the file's: one or more has no direction (render and project estimate them)");
  EXPECT_EQ(info(sphere(path("plain.xyz"), "none")), "");
}

TEST_F(SurfaceCli, RenderRecordsAndShowsTheChosenSurface) {
  const std::string cloud = sphere(path("plain.xyz"), "none");
  const auto render = [&](const std::string& flags, const std::string& name) {
    const test::CliResult r = test::run_pss("render " + cloud + " --size 64x64 -o " + path(name + ".png") + " --stats " +
                                            path(name + ".json") + flags);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return read_json(path(name + ".json"));
  };
  EXPECT_EQ(render(" --surface mls", "mls")["params"]["surface"], "mls");
  const nlohmann::json rimls = render("", "rimls");  // the default
  EXPECT_EQ(rimls["params"]["surface"], "rimls");
  EXPECT_EQ(rimls["params"]["normals"], "estimated");
  EXPECT_EQ(render(" --surface apss", "apss")["params"]["surface"], "apss");
  EXPECT_NE(read(path("mls.png")), read(path("rimls.png")));
  EXPECT_NE(read(path("mls.png")), read(path("apss.png")));
}

// --outliers: strays 1.5h to 3h off the sphere are set aside by default (counted in the
// summary and --stats), kept with --outliers keep, where they bend the projected sphere.
TEST_F(SurfaceCli, OutliersAreSetAsideUnlessKept) {
  test::SampleOptions o;
  o.count = 6000;
  const PointCloud sphere = test::sample(test::Sphere{}, o);
  const float h = test::suggested_h(sphere);
  {
    std::ofstream out(path("strays.xyz"));
    out.precision(9);
    for (const vec3& p : sphere.positions) out << p.x << ' ' << p.y << ' ' << p.z << '\n';
    for (int i = 0; i < 40; ++i) {
      const vec3 p = sphere.positions[std::size_t(i) * 100] * (1 + (1.5f + 0.04f * i) * h);
      out << p.x << ' ' << p.y << ' ' << p.z << '\n';
    }
  }
  const auto run = [&](const std::string& command, const std::string& flags, const std::string& name) {
    const test::CliResult r = test::run_pss(command + " " + path("strays.xyz") + " -o " + path(name) + " --stats " +
                                            path(name + ".json") + flags);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return std::make_pair(r.out, read_json(path(name + ".json")));
  };
  const auto [render_out, render_stats] = run("render", " --size 64x64", "r.png");
  EXPECT_EQ(render_stats["outliers_set_aside"], 40);
  EXPECT_EQ(render_stats["params"]["outliers"], "set-aside");
  EXPECT_NE(render_out.find("40 outliers set aside"), std::string::npos) << render_out;
  EXPECT_EQ(run("render", " --size 64x64 --outliers keep", "k.png").second["outliers_set_aside"], 0);
  const auto [project_out, project_stats] = run("project", "", "p.ply");
  EXPECT_EQ(project_stats["outliers_set_aside"], 40);
  EXPECT_NE(project_out.find("40 outliers set aside"), std::string::npos) << project_out;
  EXPECT_EQ(run("project", " --outliers keep", "pk.ply").second["outliers_set_aside"], 0);
  // With one h, the sphere's own points project as without the strays when they are set
  // aside (to rounding: the grid's order differs), and not when they are kept.
  {
    std::ofstream out(path("sphere.xyz"));
    out.precision(9);
    for (const vec3& p : sphere.positions) out << p.x << ' ' << p.y << ' ' << p.z << '\n';
  }
  const std::string hh = " --h " + std::to_string(h);
  ASSERT_EQ(test::run_pss("project " + path("sphere.xyz") + " -o " + path("alone.ply") + hh).exit_code, 0);
  run("project", hh, "ph.ply");
  run("project", hh + " --outliers keep", "pkh.ply");
  const auto moved = [&](const std::string& ply) {
    const test::PlyColumns a = test::read_ply_columns(path("alone.ply")), c = test::read_ply_columns(path(ply));
    double w = 0;
    for (const char* k : {"x", "y", "z"})
      for (std::size_t i = 0; i < sphere.size(); ++i) w = std::max(w, std::abs(c.columns.at(k)[i] - a.columns.at(k)[i]));
    return w;
  };
  EXPECT_LT(moved("ph.ply"), 1e-6);
  EXPECT_GT(moved("pkh.ply"), 1e-4) << "the strays do not bend the sphere: the test shows nothing";
}

TEST_F(SurfaceCli, BadValuesAreRefused) {
  const std::string cloud = sphere(path("plain.xyz"), "none");
  expect_clean_failure("render " + cloud + " --surface rbf -o " + path("o.png"), "--surface", path("o.png"));
  expect_clean_failure("project " + cloud + " --surface rbf -o " + path("o.ply"), "--surface", path("o.ply"));
  expect_clean_failure("project " + cloud + " --normals guess -o " + path("o.ply"), "--normals", path("o.ply"));
  expect_clean_failure("render " + cloud + " --outliers drop -o " + path("o.png"), "--outliers", path("o.png"));
}


// A file's normals of which some have no direction are left out, all of them, and estimated:
// the summaries say so in a line, not only "(estimated normals)" (a mesh's vertex normals,
// zero at its unused vertices, were dropped so without a word). Not with --normals estimate.
TEST_F(SurfaceCli, FileNormalsLeftOutForSomeWithoutDirectionAreSaidToBe) {
  for (const char* kind : {"some zero", "some nan"})  // NaN: as PCL writes where it fitted none
  for (const auto& [command, output] : {std::pair{"render", "r.png"}, {"project", "p.ply"}, {"mesh", "m.ply"}}) {
    const std::string cloud = sphere(path("zero.xyz"), kind);
    SCOPED_TRACE(kind);
    SCOPED_TRACE(command);
    const test::CliResult r = test::run_pss(std::string(command) + " " + cloud + " -o " + path(output));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("(estimated normals)"), std::string::npos) << r.out;
    const std::size_t at = r.out.find("left out the file's normals: ");
    ASSERT_NE(at, std::string::npos) << r.out;
    unsigned long long without = 0, points = 0;
    ASSERT_EQ(std::sscanf(r.out.c_str() + at, "left out the file's normals: %llu of %llu have no direction", &without,
                          &points),
              2)
        << r.out;
    EXPECT_GT(without, 100u);
    EXPECT_LT(without, 600u);
    EXPECT_EQ(points, 6000u);
    const test::CliResult estimated =
        test::run_pss(std::string(command) + " " + cloud + " -o " + path(output) + " --normals estimate");
    EXPECT_EQ(estimated.out.find("left out"), std::string::npos) << estimated.out;
  }
}

// Normals that do not follow the points (one direction for all, here: 45° or more off the
// sphere on 71 % of it) are left out and estimated, as --normals estimate would, by render,
// project and mesh alike, which say so and count them; the sphere comes out as with the
// estimated normals, not bent by the file's.
TEST_F(SurfaceCli, FileNormalsThatDoNotFollowThePointsAreLeftOut) {
  const std::string cloud = sphere(path("one_way.xyz"), "one way"), exact = sphere(path("exact.xyz"), "exact");
  for (const auto& [command, output] : {std::pair{"render", "r.png"}, {"project", "p.ply"}, {"mesh", "m.ply"}}) {
    SCOPED_TRACE(command);
    const std::string flags = std::string(" -o ") + path(output) + " --stats " + path("s.json") + " --surface apss";
    const test::CliResult r = test::run_pss(std::string(command) + " " + cloud + flags);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("(estimated normals)"), std::string::npos) << r.out;
    const std::size_t at = r.out.find("left out the file's normals: ");
    ASSERT_NE(at, std::string::npos) << r.out;
    unsigned long long off = 0, points = 0;
    ASSERT_EQ(std::sscanf(r.out.c_str() + at, "left out the file's normals: those of %llu samples (of %llu points) lie "
                          "more than 45 degrees off their neighbours' plane", &off, &points), 2)
        << r.out;
    EXPECT_NEAR(double(off), 0.707 * 6000, 200);
    EXPECT_EQ(points, 6000u);
    EXPECT_EQ(read_json(path("s.json"))["file_normals_off"], off);
    if (command == std::string("project")) EXPECT_LT(worst_radius_error(path("p.ply")), 1e-3);
    const test::CliResult kept = test::run_pss(std::string(command) + " " + exact + flags);
    ASSERT_EQ(kept.exit_code, 0) << kept.err;
    EXPECT_EQ(kept.out.find("left out"), std::string::npos) << kept.out;
    EXPECT_EQ(read_json(path("s.json"))["file_normals_off"], 0);
  }
}

// An OBJ whose normals come through its faces' v//vn: a vertex no face names has none, and the
// summary says that this too leaves them all out.
TEST_F(SurfaceCli, AnObjVertexNoFaceGivesANormalIsSaidToLeaveThemOut) {
  test::SampleOptions o;
  o.count = 3001;
  const std::vector<vec3> points = test::sample(test::Sphere{}, o).positions;
  std::ofstream out(path("s.obj"));
  for (const vec3& p : points) out << "v " << p.x << ' ' << p.y << ' ' << p.z << "\nvn " << p.x << ' ' << p.y << ' ' << p.z << '\n';
  for (int i = 1; i + 2 <= 3000; i += 3) out << "f " << i << "//" << i << ' ' << i + 1 << "//" << i + 1 << ' ' << i + 2 << "//" << i + 2 << '\n';
  out.close();
  const test::CliResult r = test::run_pss("render " + path("s.obj") + " --size 32x32 -o " + path("s.png"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("left out the file's normals: 1 of 3001 have no direction (zero, not finite, or in an OBJ a "
                       "vertex no face gives a normal)"),
            std::string::npos)
      << r.out;
}
}  // namespace
}  // namespace pss
