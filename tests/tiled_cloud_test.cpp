// A cloud file cut into tiles on disk (include/pss/io/tiled_cloud.hpp, issue 28): every point
// in one tile, as the in-core cloud holds it (the same origin, float positions and normals),
// and a tile's halo exactly the other points within its reach of the tile's box.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <set>
#include <string>
#include <vector>

#include "pss/io/point_cloud_file.hpp"
#include "pss/io/tiled_cloud.hpp"
#include "support/cli.hpp"
#include "support/file_bytes.hpp"

namespace pss {
namespace {

using TiledCloudTest = test::CliTest;

float distance_outside(vec3 p, const Aabb& box) {
  return glm::length(glm::max(glm::max(box.lo - p, p - box.hi), vec3(0.0f)));
}

TEST_F(TiledCloudTest, EveryPointInOneTileAsTheCloudHoldsItAndEachHaloExact) {
  const std::string file = write("t.xyz", test::torus_xyz(5000, false, 3));
  const PointCloud cloud = read_point_cloud(file);
  const TiledCloud tiles(file, dir_, 300, 1 << 16);
  EXPECT_EQ(tiles.size(), cloud.size());
  EXPECT_EQ(tiles.origin(), cloud.origin);
  EXPECT_NE(cloud.origin, glm::dvec3(0.0));
  EXPECT_TRUE(tiles.has_normals());
  ASSERT_GT(tiles.tiles(), 8);
  std::vector<int> seen(cloud.size(), 0);
  const float halo = 0.15f;
  for (int t = 0; t < tiles.tiles(); ++t) {
    const TilePoints p = tiles.load(t, halo);
    ASSERT_EQ(p.own, tiles.tile_size(t));
    ASSERT_EQ(p.positions.size(), p.index.size());
    ASSERT_EQ(p.normals.size(), p.index.size());
    const Aabb box = tiles.tile_box(t);
    std::set<std::uint64_t> in_halo;
    for (std::size_t k = 0; k < p.index.size(); ++k) {
      const std::uint64_t i = p.index[k];
      ASSERT_LT(i, cloud.size());
      EXPECT_EQ(p.positions[k], cloud.positions[i]) << "point " << i;
      EXPECT_EQ(p.normals[k], cloud.normals[i]) << "point " << i;
      if (k < p.own) {
        ++seen[i];
        EXPECT_LE(distance_outside(p.positions[k], box), 0.0f) << "a tile's own point lies in its box";
      } else {
        in_halo.insert(i);
      }
      if (k > 0 && k != p.own) EXPECT_LT(p.index[k - 1], i) << "each group in input order";
    }
    // The halo: exactly the others within `halo` of the box, by brute force.
    std::set<std::uint64_t> expected;
    for (std::size_t i = 0; i < cloud.size(); ++i)
      if (distance_outside(cloud.positions[i], box) <= halo) expected.insert(i);
    for (std::size_t k = 0; k < p.own; ++k) expected.erase(p.index[k]);
    EXPECT_EQ(in_halo, expected) << "tile " << t;
  }
  for (std::size_t i = 0; i < seen.size(); ++i) ASSERT_EQ(seen[i], 1) << "point " << i;
  // A halo wider than a tile reaches the tiles beyond the next.
  const Aabb first = tiles.tile_box(0);
  const float wide = 1.5f * (first.hi.x - first.lo.x);
  for (int t = 0; t < tiles.tiles(); t += 5) {
    const TilePoints p = tiles.load(t, wide);
    std::size_t expected = 0;
    for (const vec3& q : cloud.positions) expected += distance_outside(q, tiles.tile_box(t)) <= wide;
    EXPECT_EQ(p.index.size(), expected) << "tile " << t;
  }
}

TEST_F(TiledCloudTest, TheScratchFileGoesWithTheTilesAndACloudWithoutNormalsHasNone) {
  const std::string file = write("p.xyz", "0 0 0\n1 0 0\n0 1 0\n1 1 1\n");
  {
    const TiledCloud tiles(file, dir_ / "..", 1, 1024);
    EXPECT_FALSE(tiles.has_normals());
    EXPECT_EQ(tiles.size(), 4u);
    const TilePoints all = tiles.load(0, 10);
    EXPECT_EQ(all.index.size(), 4u) << "a halo wider than the box holds every point";
    EXPECT_EQ(tiles.load(0, 1e30f).index.size(), 4u);
    EXPECT_TRUE(all.normals.empty());
  }
  for (const auto& entry : std::filesystem::directory_iterator(dir_ / ".."))
    EXPECT_EQ(entry.path().filename().string().find(".pss-scratch"), std::string::npos) << entry.path();
}

// Normals of which one has no direction (zero, or NaN as PCL writes where it fitted none) are
// left out in core (all estimated, points/sample_normals.hpp): tiles take the cloud as
// having none.
TEST_F(TiledCloudTest, NormalsOneOfWhichHasNoDirectionAreNone) {
  for (const char* odd : {"0 0 0", "nan 0 1", "0 inf 0"}) {
    SCOPED_TRACE(odd);
    const std::string file =
        write("n.xyz", std::string("0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 ") + odd + "\n1 1 1 0 0 1\n");
    EXPECT_FALSE(TiledCloud(file, dir_, 1, 1024).has_normals());
  }
  EXPECT_TRUE(TiledCloud(write("d.xyz", "0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 0 0 2.5\n"), dir_, 1, 1024).has_normals());
}

// Tiles for one point each of 20,000 filling a cube would be 142³: their number is capped.
TEST_F(TiledCloudTest, TheTilesNumberAtMost65536) {
  std::string text;
  for (int i = 0; i < 20000; ++i)
    text += std::to_string(i % 37) + " " + std::to_string(i % 41) + " " + std::to_string(i % 43) + "\n";
  const TiledCloud tiles(write("cube.xyz", text), dir_, 1, 1 << 16);
  EXPECT_LE(tiles.tiles(), 1 << 16);
  EXPECT_GT(tiles.tiles(), 1 << 14);
  std::uint64_t total = 0;
  for (int t = 0; t < tiles.tiles(); ++t) total += tiles.tile_size(t);
  EXPECT_EQ(total, 20000u);
}

}  // namespace
}  // namespace pss
