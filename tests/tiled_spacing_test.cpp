// A cloud's spacing estimated tile by tile (include/pss/tiles/spacing.hpp, issue 28): the
// in-core estimate to the last bit, whatever the tiles.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "pss/io/point_cloud_file.hpp"
#include "pss/points/spacing.hpp"
#include "pss/tiles/spacing.hpp"
#include "support/cli.hpp"

namespace pss {
namespace {

using TiledSpacingTest = test::CliTest;

// A torus far from the world's origin whose sampling is eight times denser on one side
// (x > 0): the k-th distances vary, and queries near a tile's edge need its neighbours.
std::string uneven_torus(int n) {
  std::string text;
  char line[160];
  for (int i = 0; i < n; ++i) {
    const double u = 2 * M_PI * std::fmod(0.6180339887 * i, 1.0), v = 2 * M_PI * std::fmod(0.7548776662 * i, 1.0);
    const double x = (1 + 0.35 * std::cos(v)) * std::cos(u);
    if (x < 0 && i % 8 != 0) continue;
    std::snprintf(line, sizeof line, "%.12f %.12f %.12f\n", 596700 + x, 4000000 + (1 + 0.35 * std::cos(v)) * std::sin(u),
                  0.35 * std::sin(v));
    text += line;
  }
  return text;
}

void expect_same(const SpacingEstimate& a, const SpacingEstimate& b) {
  EXPECT_EQ(a.k, b.k);
  EXPECT_EQ(a.mean_nearest, b.mean_nearest);
  EXPECT_EQ(a.median_kth, b.median_kth);
  EXPECT_EQ(a.min_kth, b.min_kth);
  EXPECT_EQ(a.max_kth, b.max_kth);
  EXPECT_EQ(a.suggested_h, b.suggested_h);
}

TEST_F(TiledSpacingTest, TheTilesGiveTheInCoreEstimateToTheLastBit) {
  const std::string file = write("t.xyz", uneven_torus(40000));
  const PointCloud cloud = read_point_cloud(file);
  ASSERT_GT(cloud.size(), 20000u);
  for (const std::uint64_t per_tile : {300u, 5000u}) {
    SCOPED_TRACE(per_tile);
    const TiledCloud tiles(file, dir_, per_tile, 1 << 16);
    if (per_tile == 300) EXPECT_GT(tiles.tiles(), 20);
    for (const std::size_t samples : {std::size_t(20000), std::size_t(997)})
      expect_same(estimate_spacing(tiles, 15, samples), estimate_spacing(cloud.positions, 15, samples));
    expect_same(estimate_spacing(tiles, 3), estimate_spacing(cloud.positions, 3));
  }
  const SpacingEstimate e = estimate_spacing(cloud.positions);
  EXPECT_GT(e.max_kth, 2 * e.min_kth) << "the sampling is uneven";
}

TEST_F(TiledSpacingTest, TwoPointsAreTheLeastAndCoincidentPointsHaveNoSpacing) {
  const TiledCloud two(write("two.xyz", "0 0 0\n3 4 0\n"), dir_, 1, 1024);
  EXPECT_DOUBLE_EQ(estimate_spacing(two).suggested_h, 5);
  const TiledCloud one(write("one.xyz", "1 2 3\n"), dir_, 1, 1024);
  EXPECT_NE(test::error_of([&] { estimate_spacing(one); }), "");
  const TiledCloud same(write("same.xyz", "1 2 3\n1 2 3\n1 2 3\n"), dir_, 1, 1024);
  EXPECT_NE(test::error_of([&] { estimate_spacing(same); }).find("coincide"), std::string::npos);
}

}  // namespace
}  // namespace pss
