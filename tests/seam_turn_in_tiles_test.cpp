// The seams' turn tile by tile (src/tiles/seam_turn_in_tiles.cpp, issue 28): given the same
// oriented normals, the tiles turn what the in-core turn (points/turn_flipped_normals.hpp)
// turns, normal for normal: its joins, patches, evidence, groups and stragglers' says.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "../src/tiles/tiled_samples.hpp"
#include "pss/io/point_cloud_file.hpp"
#include "pss/points/turn_flipped_normals.hpp"
#include "support/cli.hpp"
#include "support/file_bytes.hpp"
#include "support/shapes.hpp"

namespace pss {
namespace {

using SeamTurnInTiles = test::CliTest;

// A sphere's outward normal with a cap above z = 0.4 flipped (a seam round it, which the
// groups' turn mends) and every 97th turned half round and flipped (alone in its patch: a
// straggler, which the stragglers' turn mends).
vec3 given_normal(vec3 p, std::size_t i) {
  vec3 n = glm::normalize(p);
  if (p.z > 0.4f) n = -n;
  if (i % 97 == 0) n = -glm::normalize(n + vec3(0.8f, -0.6f, 0.4f) * 0.9f);
  return n;
}

TEST_F(SeamTurnInTiles, TilesTurnWhatTheInCoreTurnTurns) {
  // Three times sparser beyond x = 0.2: the widths differ across the tiles' seams there, so a
  // pair within the wider sample's half-support is seen from that sample's tile alone.
  test::SampleOptions o;
  o.count = 9000;
  std::vector<vec3> points;
  for (const vec3& p : test::sample(test::Sphere{}, o).positions)
    if (p.x < 0.2f || points.size() % 3 == 0) points.push_back(p);
  const std::string file = write("sphere.xyz", test::xyz_text(points));
  ProjectionParams params = ProjectionParams::from_h(test::suggested_h(read_point_cloud(file)));
  params.support = Support::adaptive;
  params.outliers = OutlierPolicy::keep;
  const TiledCloud cloud(file, dir_, 700, 1 << 16);
  ASSERT_GT(cloud.tiles(), 6);
  Stats stats;
  const TiledSamples s = tiled_samples(cloud, params, false, Backend::cpu, 5000, dir_, 1 << 16, stats, local_farm());
  ASSERT_TRUE(s.merge.empty());
  const UnitSets sets = s.sets(cloud);
  // The given normals, as the orientation leaves them: by tile, one piece that does not turn.
  OrientedInTiles given;
  given.by_tile = std::make_unique<BucketFile>(dir_, cloud.tiles(), sizeof(Oriented), 1 << 16);
  given.pieces = {{0}, {0}, {0}};
  std::vector<vec3> unit(points.size());
  for (int t = 0; t < cloud.tiles(); ++t) {
    const UnitSet set = sets.load(t);
    for (std::size_t i = 0; i < set.points.own; ++i) {
      const std::uint64_t k = set.points.index[i];
      unit[std::size_t(k)] = set.unit[i];
      const Oriented r{k, set.unit[i], given_normal(points[std::size_t(k)], std::size_t(k)), 0,
                       ProjectionStatus::converged, true};
      given.by_tile->append(t, &r);
    }
  }
  given.by_tile->flush();
  const std::size_t turned_in_tiles = turn_seams_in_tiles(sets, given, local_farm());

  SupportGrid grid(unit, s.h, s.kappa);
  const std::span<const int> original = grid.original_index();
  std::vector<vec3> in_core(original.size());
  for (std::size_t k = 0; k < original.size(); ++k)
    in_core[k] = given_normal(points[std::size_t(original[k])], std::size_t(original[k]));
  const std::size_t turned_in_core = turn_flipped_normals(grid, in_core);
  EXPECT_GT(turned_in_core, 1000u) << "the cap";
  EXPECT_EQ(turned_in_tiles, turned_in_core);

  std::vector<char> turned(points.size(), 0);
  for (int t = 0; t < cloud.tiles(); ++t)
    given.by_tile->for_each_record<Oriented>(t, [&](const Oriented& r) { turned[r.index] = given.turned(r); });
  std::size_t differ = 0, stragglers_turned = 0, outward = 0;
  for (std::size_t k = 0; k < original.size(); ++k) {
    const auto i = std::size_t(original[k]);
    const vec3 before = given_normal(points[i], i);
    const bool turned_here = glm::dot(in_core[k], before) < 0;
    differ += turned_here != bool(turned[i]);
    stragglers_turned += turned_here && i % 97 == 0;
    outward += glm::dot(in_core[k], points[i]) > 0;
  }
  EXPECT_EQ(differ, 0u);
  EXPECT_GT(stragglers_turned, 30u);
  EXPECT_EQ(outward, points.size()) << "the cap and the stragglers turned outward";
}

}  // namespace
}  // namespace pss
