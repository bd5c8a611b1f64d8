// The adaptive widths tile by tile (include/pss/tiles/support.hpp, issue 28): every sample's
// h_i equal to the in-core one to the last bit, whatever the tiles, where the widths widen
// (a torus sparse on one side, strays beside it), where the noise sets them (a sphere noisy
// on a cap), and where neighbours tie (a lattice, whose every sample has many neighbours at
// equal distances).
#include <gtest/gtest.h>

#include <cstdio>
#include <random>
#include <string>

#include "pss/core/error.hpp"
#include "pss/io/point_cloud_file.hpp"
#include "pss/points/spacing.hpp"
#include "pss/points/support.hpp"
#include "pss/tiles/support.hpp"
#include "support/cli.hpp"
#include "support/file_bytes.hpp"
#include "support/shapes.hpp"

namespace pss {
namespace {

using TiledSupportTest = test::CliTest;

ProjectionParams adaptive(float h) {
  ProjectionParams params = ProjectionParams::from_h(h);
  params.support = Support::adaptive;
  return params;
}

// The widths of the file's cloud in core and in tiles of each size, the same to the last
// bit; returns the in-core ones.
SupportWidths expect_tiles_as_in_core(const std::string& file, const std::filesystem::path& dir, float h,
                                      std::initializer_list<std::uint64_t> per_tile) {
  const PointCloud cloud = read_point_cloud(file);
  const SupportWidths in_core = support_widths(cloud.positions, adaptive(h));
  for (const std::uint64_t size : per_tile) {
    SCOPED_TRACE(size);
    const TiledCloud tiles(file, dir, size, 1 << 16);
    EXPECT_GT(tiles.tiles(), 1);
    const SupportWidths tiled = support_widths(tiles, adaptive(h));
    std::size_t differ = 0;
    for (std::size_t i = 0; i < cloud.size(); ++i) differ += tiled.h[i] != in_core.h[i];
    EXPECT_EQ(differ, 0u) << "of " << cloud.size() << " widths differ from the in-core ones";
    EXPECT_EQ(std::tie(tiled.least, tiled.median, tiled.largest),
              std::tie(in_core.least, in_core.median, in_core.largest));
  }
  return in_core;
}

std::size_t widened(const SupportWidths& w, float h) {
  std::size_t count = 0;
  for (float width : w.h) count += width > h;
  return count;
}

// A torus sampled 8 times sparser where x < 0, with 1 % strays strewn through its box.
TEST_F(TiledSupportTest, ASparseSideAndStraysWidenInTilesAsInCore) {
  std::string text = test::torus_xyz(30000, true, 0);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> across(-1.4, 1.4);
  char line[120];
  for (int i = 0; i < 170; ++i) {
    std::snprintf(line, sizeof line, "%.12f %.12f %.12f\n", 596700 + across(rng), 4000000 + across(rng),
                  0.4 * across(rng));
    text += line;
  }
  const std::string file = write("torus.xyz", text);
  const float h = float(estimate_spacing(read_point_cloud(file).positions).suggested_h);
  const SupportWidths w = expect_tiles_as_in_core(file, dir_, h, {400, 4000});
  EXPECT_GT(widened(w, h), 1000u) << "the sparse side does not widen: no test";
}

// A unit sphere noisy (σ = 0.06) above z = 0.3: the noise queries' regions and their spread
// cross the tiles' edges.
TEST_F(TiledSupportTest, TheNoiseWidensInTilesAsInCore) {
  test::SampleOptions o;
  o.count = 8000;
  PointCloud cloud = test::sample(test::Sphere{}, o);
  std::mt19937 rng(3);
  std::normal_distribution<float> offset(0.0f, 0.06f);
  for (vec3& p : cloud.positions)
    if (p.z > 0.3f) p += offset(rng) * glm::normalize(p);
  const std::string file = write("cap.xyz", test::xyz_text(cloud.positions));
  const SpacingEstimate e = estimate_spacing(read_point_cloud(file).positions);
  const SupportWidths w = expect_tiles_as_in_core(file, dir_, float(e.median_kth), {300, 2000});
  EXPECT_GT(widened(w, float(e.median_kth)), 2000u) << "the noise does not widen: no test";
}

// The same sphere 10^30 across (unit_frame.hpp takes any scale): a halo point's distance to
// its tile, squared in float, overflowed there and the halo lost it.
TEST_F(TiledSupportTest, ACloudOfHugeCoordinatesWidensInTilesAsInCore) {
  test::SampleOptions o;
  o.count = 6000;
  PointCloud cloud = test::sample(test::Sphere{}, o);
  for (std::size_t i = 0; i < cloud.size(); i += 5) cloud.positions[i] *= 1.0f + 0.03f * float(i % 7);  // some noise
  for (vec3& p : cloud.positions) p *= 1e30f;
  const std::string file = write("huge.xyz", test::xyz_text(cloud.positions));
  const SpacingEstimate e = estimate_spacing(read_point_cloud(file).positions);
  expect_tiles_as_in_core(file, dir_, float(e.suggested_h), {300});
}

// A square lattice, one corner 3 times sparser: every sample's k nearest end among ties,
// which a tile's tree and the whole cloud's would break differently.
TEST_F(TiledSupportTest, NeighboursAtEqualDistancesAreTheSameInTilesAsInCore) {
  std::vector<vec3> points;
  for (int y = 0; y < 120; ++y)
    for (int x = 0; x < 120; ++x)
      if ((x < 60 && y < 60) ? (x % 3 == 0 && y % 3 == 0) : true) points.push_back(vec3(float(x), float(y), 0.0f));
  const std::string file = write("lattice.xyz", test::xyz_text(points));
  const SupportWidths w = expect_tiles_as_in_core(file, dir_, 4.0f, {250, 3000});
  EXPECT_GT(widened(w, 4.0f), 300u) << "the sparse corner does not widen: no test";
}

TEST_F(TiledSupportTest, OneWidthForAllAndACloudOfRows) {
  const std::string file = write("torus.xyz", test::torus_xyz(3000, false, 0));
  ProjectionParams global = ProjectionParams::from_h(0.05f);
  global.support = Support::global;
  const SupportWidths w = support_widths(TiledCloud(file, dir_, 300, 1 << 16), global);
  EXPECT_EQ(w.h, std::vector<float>(3000, 0.05f));
  EXPECT_THROW(support_widths(TiledCloud(file, dir_, 300, 1 << 16), adaptive(-1.0f)), Error);

  // Rows 2 apart, each sampled every 0.1: refused, with why.
  std::vector<vec3> rows;
  for (int r = 0; r < 20; ++r)
    for (int s = 0; s < 200; ++s) rows.push_back(vec3(0.1f * float(s), 2.0f * float(r), 0.0f));
  const std::string rows_file = write("rows.xyz", test::xyz_text(rows));
  try {
    support_widths(TiledCloud(rows_file, dir_, 500, 1 << 16), adaptive(1.0f));
    ADD_FAILURE() << "a cloud of rows was not refused";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("sampled in rows"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace pss
