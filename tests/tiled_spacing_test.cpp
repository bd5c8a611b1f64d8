// A cloud's spacing estimated tile by tile (include/pss/tiles/spacing.hpp, issue 28): the
// in-core estimate to the last bit, whatever the tiles, on a torus sampled eight times
// denser on one side (the k-th distances vary, and queries near a tile's edge need its
// neighbours).
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "pss/io/point_cloud_file.hpp"
#include "pss/points/spacing.hpp"
#include "pss/tiles/spacing.hpp"
#include "support/cli.hpp"
#include "support/file_bytes.hpp"
#include "support/shapes.hpp"

namespace pss {
namespace {

using TiledSpacingTest = test::CliTest;

// Every field of the estimate, to the last bit.
void expect_same(const SpacingEstimate& a, const SpacingEstimate& b) {
  EXPECT_EQ(std::tie(a.k, a.mean_nearest, a.median_kth, a.min_kth, a.max_kth, a.noise, a.suggested_h),
            std::tie(b.k, b.mean_nearest, b.median_kth, b.min_kth, b.max_kth, b.noise, b.suggested_h));
}

TEST_F(TiledSpacingTest, TheTilesGiveTheInCoreEstimateToTheLastBit) {
  const std::string file = write("t.xyz", test::torus_xyz(40000, true, 0));
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

// A noisy torus, whose noise sets h: each query's noise is fitted to the points within a
// reach of several times the noise, beyond its k-th neighbour, and the tiles' halos hold them.
// And a sphere under noise of twice the spacing beside a block of points that fill a volume:
// reaches of up to 24 k-th distances, read through the thinned grids (points/noise.hpp).
TEST_F(TiledSpacingTest, TheNoiseIsTheInCoreNoiseToTheLastBit) {
  test::SampleOptions o;
  o.count = 8000;
  o.noise = 0.05f;
  std::vector<vec3> torus = test::sample(test::Torus{}, o).positions;
  o.count = 3000;
  o.noise = 0.3f;
  std::vector<vec3> sphere = test::sample(test::Sphere{}, o).positions;
  for (int i = 0; i < 1000; ++i)
    sphere.push_back(vec3(2.5f + 0.001f * float(i % 10), 0.01f * float(i / 10 % 10), 0.01f * float(i / 100)) +
                     0.3f * vec3(std::sin(float(i)), std::cos(float(3 * i)), std::sin(float(7 * i))));
  // (The sphere's reaches span most of it: smaller tiles only load it again, halo by halo.)
  for (const auto& [name, points, smallest] : {std::tuple{"noisy.xyz", torus, 300u}, {"thick.xyz", sphere, 1500u}}) {
    SCOPED_TRACE(name);
    std::string text;
    for (const vec3& p : points) text += std::to_string(p.x) + " " + std::to_string(p.y) + " " + std::to_string(p.z) + "\n";
    const std::string file = write(name, text);
    const PointCloud cloud = read_point_cloud(file);
    const SpacingEstimate e = estimate_spacing(cloud.positions);
    ASSERT_GT(e.suggested_h, e.median_kth) << "the noise sets h";
    for (const std::uint64_t per_tile : {std::uint64_t(smallest), std::uint64_t(3000)}) {
      SCOPED_TRACE(per_tile);
      expect_same(estimate_spacing(TiledCloud(file, dir_, per_tile, 1 << 16)), e);
    }
  }
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
