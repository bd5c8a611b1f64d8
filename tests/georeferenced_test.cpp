// Clouds far from the world's origin (cloud.hpp): a sphere of radius 5 m at UTM-like
// coordinates (4·10⁶ m, where a float's step is 0.25 m, about the samples' spacing) must
// read, project and render as it does at the origin. The truth is the analytic sphere.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

#include <glm/ext/vector_double3.hpp>
#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include "pss/io/ply.hpp"
#include "pss/io/tiled_cloud.hpp"
#include "pss/io/point_cloud_file.hpp"
#include "pss/io/xyz.hpp"
#include "pss/points/cloud.hpp"
#include "pss/points/unit_frame.hpp"
#include "support/cli.hpp"

namespace {

using glm::dvec3;
using pss::PointCloud;
using pss::vec3;
using GeoTest = pss::test::CliTest;

const dvec3 kCentre(500123.25, 4000456.5, 310.75);
constexpr double kRadius = 5.0;

// A Fibonacci sphere of n points: 0.28 m between neighbours for n = 4000.
std::vector<dvec3> sphere(int n) {
  std::vector<dvec3> p;
  const double golden = M_PI * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < n; ++i) {
    const double z = 1.0 - 2.0 * (i + 0.5) / n, r = std::sqrt(1.0 - z * z), a = golden * i;
    p.push_back(kCentre + kRadius * dvec3(r * std::cos(a), r * std::sin(a), z));
  }
  return p;
}

std::string text_of(const std::vector<dvec3>& points, const char* prefix) {
  std::string s;
  char line[128];
  for (const dvec3& p : points) {
    std::snprintf(line, sizeof line, "%s%.17g %.17g %.17g\n", prefix, p.x, p.y, p.z);
    s += line;
  }
  return s;
}

// The largest distance of the cloud's world positions from `expected`, point by point.
double largest_error(const PointCloud& cloud, const std::vector<dvec3>& expected) {
  EXPECT_EQ(cloud.size(), expected.size());
  double worst = 0;
  for (std::size_t i = 0; i < cloud.size() && i < expected.size(); ++i)
    worst = std::max(worst, glm::length(cloud.world(i) - expected[i]));
  return worst;
}

// The largest distance of the cloud's world positions from the sphere.
double largest_distance_from_sphere(const PointCloud& cloud) {
  double worst = 0;
  for (std::size_t i = 0; i < cloud.size(); ++i)
    worst = std::max(worst, std::abs(glm::length(cloud.world(i) - kCentre) - kRadius));
  return worst;
}

TEST(LocalOrigin, ZeroNearTheOriginElseAPowerOfTwoGridPointNearTheCentre) {
  EXPECT_EQ(pss::local_origin(dvec3(-1, 0, 2), dvec3(3, 1, 4)), dvec3(0.0));
  EXPECT_EQ(pss::local_origin(dvec3(5, 5, 5), dvec3(8, 7, 6)), dvec3(0.0));  // within 4 extents
  const dvec3 o = pss::local_origin(dvec3(500100, 4000400, 300), dvec3(500105, 4000410, 303));
  EXPECT_EQ(o, dvec3(500096, 4000400, 304));  // the centre rounded to multiples of 16 ≥ 10
  // Axis by axis: only z is far for its extent.
  EXPECT_EQ(pss::local_origin(dvec3(0.3, 0, 100), dvec3(1.2, 1, 101)), dvec3(0, 0, 101));
  EXPECT_EQ(pss::local_origin(dvec3(7e6, 0, 0), dvec3(7e6, 0, 0)), dvec3(0.0));  // one position
}

TEST(LocalOrigin, FloatPositionsComeBackExactly) {
  // A float file far from the origin: position minus origin is exact, so a float written
  // back equals the one read.
  // Far on every axis, and far on one only (near axes whose values are small beside the
  // rounding step would not come back so if they were shifted too).
  for (const dvec3 far : {dvec3(4e6, -2.5e5, 1234.5), dvec3(0, 0, 100)}) {
    std::vector<dvec3> world;
    for (int i = 0; i < 1000; ++i)
      world.emplace_back(dvec3(vec3(far + dvec3(0.0037 * i, 0.0011 * i, 0.0013 * i) + dvec3(0.3, 0, 0))));
    PointCloud cloud;
    pss::set_world_positions(cloud, world);
    EXPECT_NE(cloud.origin, dvec3(0.0));
    for (std::size_t i = 0; i < world.size(); ++i) ASSERT_EQ(vec3(cloud.world(i)), vec3(world[i])) << i;
    // Given as floats (a float file's reader keeps them so), the same origin and positions.
    std::vector<vec3> floats;
    for (const dvec3& w : world) floats.push_back(vec3(w));
    PointCloud from_floats;
    pss::set_world_positions(from_floats, std::move(floats));
    EXPECT_EQ(from_floats.origin, cloud.origin);
    EXPECT_EQ(from_floats.positions, cloud.positions);
  }
}

// A binary PLY of floats far from zero (read into floats, offset in place) keeps every float.
TEST_F(GeoTest, AFloatPlyFarFromZeroKeepsItsFloats) {
  std::vector<vec3> points;
  for (int i = 0; i < 100; ++i) points.push_back(vec3(kCentre + dvec3(0.25 * i, -0.5 * i, 0.125 * i)));
  std::string ply = "ply\nformat binary_little_endian 1.0\nelement vertex 100\nproperty float x\nproperty float y\n"
                    "property float z\nend_header\n";
  ply.append(reinterpret_cast<const char*>(points.data()), points.size() * sizeof(vec3));
  const PointCloud cloud = pss::read_point_cloud(write("far.ply", ply));
  EXPECT_NE(cloud.origin, dvec3(0.0));
  ASSERT_EQ(cloud.size(), points.size());
  for (std::size_t i = 0; i < points.size(); ++i) ASSERT_EQ(vec3(cloud.world(i)), points[i]) << i;
}

TEST_F(GeoTest, EveryReaderKeepsTheDigitsAndTheWritersPutThemBack) {
  const std::vector<dvec3> points = sphere(400);
  // Well below a float's 0.25 m step at 4·10⁶ m (the error before the origin was kept).
  constexpr double kTolerance = 1e-6;
  const std::string pcd = "VERSION 0.7\nFIELDS x y z\nSIZE 8 8 8\nTYPE F F F\nCOUNT 1 1 1\nWIDTH 400\nHEIGHT 1\n"
                          "POINTS 400\nDATA ascii\n";
  for (const auto& [name, bytes] : {std::pair<std::string, std::string>{"a.xyz", text_of(points, "")},
                                    {"a.obj", text_of(points, "v ")},
                                    {"a.pcd", pcd + text_of(points, "")}}) {
    const PointCloud cloud = pss::read_point_cloud(write(name, bytes));
    EXPECT_LT(largest_error(cloud, points), kTolerance) << name;
  }
  // ASCII STL: facets of three consecutive points, each vertex once.
  std::string stl = "solid sphere\n";
  for (std::size_t i = 0; i + 2 < points.size(); i += 3)
    stl += "facet normal 0 0 1\nouter loop\n" + text_of({points[i], points[i + 1], points[i + 2]}, "vertex ") +
           "endloop\nendfacet\n";
  EXPECT_LT(largest_error(pss::read_point_cloud(write("a.stl", stl + "endsolid sphere\n")),
                          std::vector<dvec3>(points.begin(), points.begin() + 399)),
            kTolerance);

  const PointCloud cloud = pss::read_point_cloud(path("a.xyz"));
  pss::write_ply(path("b.ply"), cloud);
  EXPECT_NE(read(path("b.ply")).find("property double x"), std::string::npos);
  EXPECT_LT(largest_error(pss::read_point_cloud(path("b.ply")), points), kTolerance);
  pss::write_xyz(path("b.xyz"), cloud);
  EXPECT_LT(largest_error(pss::read_point_cloud(path("b.xyz")), points), kTolerance);
}

// `pss info` prints world bounds with every digit the cloud keeps: 4000456.1234 needs 11,
// more than a fixed %.10g gives, and its float about the origin tells the 4 apart.
TEST_F(GeoTest, InfoPrintsTheWorldBoundsDigitForDigit) {
  write("g.xyz", "500123.25 4000456.1234 310.75\n500128.125 4000461.5678 315.5\n");
  const pss::test::CliResult r = pss::test::run_pss("info " + path("g.xyz"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("bounds          [500123.25, 500128.125] x [4000456.1234, 4000461.5678] x [310.75, 315.5]\n"),
            std::string::npos)
      << r.out;
}

TEST_F(GeoTest, ProjectAndRenderOnTheSphere) {
  write("s.xyz", text_of(sphere(4000), ""));
  const pss::test::CliResult project = pss::test::run_pss("project " + path("s.xyz") + " -o " + path("p.ply"));
  ASSERT_EQ(project.exit_code, 0) << project.err;
  // The PSS of a sampled sphere lies on it, to the sampling's smoothing (at the origin: 4e-5 m).
  EXPECT_LT(largest_distance_from_sphere(pss::read_point_cloud(path("p.ply"))), 1e-3);

  // --look-at is in world coordinates: looking at the centre from the side puts the sphere
  // in the middle of the image.
  const std::string look = std::to_string(kCentre.x) + "," + std::to_string(kCentre.y) + "," +
                           std::to_string(kCentre.z);
  const pss::test::CliResult render = pss::test::run_pss("render " + path("s.xyz") + " --size 64x64 --look-at " + look +
                                                         " -o " + path("r.png") + " --hits " + path("h.ply"));
  ASSERT_EQ(render.exit_code, 0) << render.err;
  const PointCloud hits = pss::read_point_cloud(path("h.ply"));
  ASSERT_GT(hits.size(), 500u);
  EXPECT_LT(largest_distance_from_sphere(hits), 1e-3);
  // The hits' pixels are centred: PLY properties px, py are read back as scalars.
  double mean_x = 0, mean_y = 0;
  for (const pss::ScalarProperty& s : hits.scalars)
    for (double v : s.values) (s.name == "px" ? mean_x : mean_y) += v / double(hits.size());
  EXPECT_NEAR(mean_x, 31.5, 1.0);
  EXPECT_NEAR(mean_y, 31.5, 1.0);
}

// One point far from the rest (a scanner's (0,0,0) beside a georeferenced scan; a stray at 10⁶
// beside a cloud at zero) decided the origin and the unit frame's centre by the box: the scan
// was read on quarter-metre steps and projected off its sphere (a new user's trial). The
// bulk decides now (core/bulk_sample.hpp), in core and in tiles alike.
TEST_F(GeoTest, AStrayFarFromTheRestTakesNothingFromItsDigits) {
  std::vector<dvec3> scan = sphere(4000);
  std::vector<dvec3> at_zero;
  for (const dvec3& p : scan) at_zero.push_back(p - kCentre);
  for (const auto& [name, points, stray] :
       {std::tuple{std::string("georeferenced.xyz"), scan, dvec3(0.0)},
        std::tuple{std::string("at_zero.xyz"), at_zero, dvec3(1e6, 0, 0)}}) {
    std::vector<dvec3> with_stray = points;
    with_stray.insert(with_stray.begin() + 100, stray);
    write(name, text_of(with_stray, ""));
    const PointCloud cloud = pss::read_point_cloud(path(name));
    ASSERT_EQ(cloud.size(), with_stray.size());
    double worst = 0;
    for (std::size_t i = 0; i < cloud.size(); ++i)
      if (i != 100) worst = std::max(worst, glm::length(cloud.world(i) - with_stray[i]));
    EXPECT_LT(worst, 1e-6) << name;
    const pss::TiledCloud tiles(path(name), dir_, 1000, 1 << 16);
    EXPECT_EQ(tiles.origin(), cloud.origin) << name;
    EXPECT_EQ(tiles.unit_frame().centre, pss::unit_frame(cloud.positions).centre) << name;
    EXPECT_LT(glm::length(pss::unit_frame(cloud.positions).centre - (points[0] - cloud.origin)), 2 * kRadius) << name;

    const pss::test::CliResult project = pss::test::run_pss("project " + path(name) + " -o " + path("p.ply"));
    ASSERT_EQ(project.exit_code, 0) << project.err;
    const PointCloud projected = pss::read_point_cloud(path("p.ply"));
    ASSERT_EQ(projected.size(), with_stray.size());
    const dvec3 centre = name == "at_zero.xyz" ? dvec3(0.0) : kCentre;
    double off = 0;
    for (std::size_t i = 0; i < projected.size(); ++i)
      if (i != 100) off = std::max(off, std::abs(glm::length(projected.world(i) - centre) - kRadius));
    EXPECT_LT(off, 1e-3) << name;  // as without the stray (ProjectAndRenderOnTheSphere)
  }
  // 10²⁰ away: the rest still has its spacing, and the diagonal is printed, not "inf".
  std::vector<dvec3> far_off = at_zero;
  far_off.push_back(dvec3(1e20, 0, 0));
  write("far_off.xyz", text_of(far_off, ""));
  const pss::test::CliResult far_info = pss::test::run_pss("info " + path("far_off.xyz"));
  EXPECT_EQ(far_info.exit_code, 0) << far_info.err;
  EXPECT_NE(far_info.out.find("(diagonal 1e+20)"), std::string::npos) << far_info.out;
  // 10³⁰ away the rest is below float's reach in the cloud's frame: the estimate says why.
  std::vector<dvec3> beyond = at_zero;
  beyond.push_back(dvec3(1e30, 0, 0));
  write("beyond.xyz", text_of(beyond, ""));
  const pss::test::CliResult info = pss::test::run_pss("info " + path("beyond.xyz"));
  EXPECT_NE(info.exit_code, 0);
  EXPECT_NE(info.err.find("nearly all do beside a few very far from the rest"), std::string::npos) << info.err;
}

// The ray through the image's centre passes through --look-at: a world point (0.1 m apart
// here, where a float has 0.25 m steps) and the eye --stats writes is a world position.
TEST_F(GeoTest, LookAtAndTheStatsEyeAreWorldPositions) {
  write("s.xyz", text_of(sphere(4000), ""));
  const dvec3 look = kCentre + dvec3(1.3, 2.1, 0.1);
  char text[128];
  std::snprintf(text, sizeof text, "%.17g,%.17g,%.17g", look.x, look.y, look.z);
  const pss::test::CliResult render =
      pss::test::run_pss("render " + path("s.xyz") + " --size 65x65 --zoom 4 --look-at " + text + " --stats " +
                         path("s.json") + " -o " + path("r.png") + " --hits " + path("h.ply"));
  ASSERT_EQ(render.exit_code, 0) << render.err;
  const nlohmann::json stats = nlohmann::json::parse(read(path("s.json")));
  const dvec3 eye(stats["camera"]["eye"][0].get<double>(), stats["camera"]["eye"][1].get<double>(),
                  stats["camera"]["eye"][2].get<double>());
  const PointCloud hits = pss::read_point_cloud(path("h.ply"));
  std::optional<dvec3> centre_hit;
  for (std::size_t i = 0; i < hits.size(); ++i)
    if (hits.scalars[0].values[i] == 32 && hits.scalars[1].values[i] == 32) centre_hit = hits.world(i);
  ASSERT_TRUE(centre_hit);
  const dvec3 along = glm::normalize(look - eye);
  const dvec3 off = *centre_hit - eye - glm::dot(*centre_hit - eye, along) * along;
  EXPECT_LT(glm::length(off), 0.01);
}

}  // namespace
