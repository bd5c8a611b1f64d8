// pss project tile by tile (include/pss/tiles/project.hpp, issue 28): the points of
// project_cloud, in its order, to the last bit, whatever the tiles (each tile's grid takes the
// whole cloud's cells, spatial/support_layout.hpp, so every sum runs in one order); the
// normals facing as in core, whose signs the tiles agree on across their seams.
#include <gtest/gtest.h>

#include <cstdio>
#include <functional>
#include <random>
#include <string>

#include "pss/core/error.hpp"
#include "pss/io/point_cloud_file.hpp"
#include "pss/points/facing_vote.hpp"
#include "pss/tiles/orient.hpp"
#include "pss/tiles/project.hpp"
#include "support/cli.hpp"
#include "support/file_bytes.hpp"
#include "support/mesh_readers.hpp"
#include "support/shapes.hpp"

namespace pss {
namespace {

using TiledProjectTest = test::CliTest;

struct Compared {
  float farthest = 0;               // the largest distance between the two projections of a point
  std::size_t facing_apart_on = 0;  // normals facing apart where `on` holds in core
  std::size_t apart = 0;            // points whose two projections differ at all
  std::size_t facing_apart = 0;     // normals facing apart
  std::size_t status_differ = 0;
  std::size_t tiles = 0;
};

// The file's cloud projected in tiles of `per_tile` points, against its projection in core.
Compared compare(const CloudProjection& in_core, const std::string& file, const std::filesystem::path& dir,
                 const ProjectionParams& params, std::uint64_t per_tile, std::size_t window,
                 const std::function<bool(vec3)>& on = [](vec3) { return true; }) {
  Stats stats;
  const TiledCloud tiles(file, dir, per_tile, 1 << 16);
  const TiledProjection tiled(tiles, params, Backend::cpu, dir, window, 1 << 16, stats);
  EXPECT_EQ(tiled.normals_used(), in_core.normals);
  EXPECT_EQ(tiled.outliers().set_aside, in_core.outliers.set_aside);
  EXPECT_EQ(tiled.widths().merged_count, in_core.widths.merged_count);
  EXPECT_EQ(tiled.counts().converged, in_core.counts.converged);
  EXPECT_EQ(tiled.counts().not_converged, in_core.counts.not_converged);
  Compared c;
  c.tiles = std::size_t(tiles.tiles());
  std::uint64_t next = 0;
  tiled.read_in_order([&](const ProjectedWindow& w) {
    EXPECT_EQ(w.first, next);
    for (std::size_t k = 0; k < w.positions.size(); ++k) {
      const std::size_t i = std::size_t(w.first + k);
      const float d = glm::length(w.positions[k] - in_core.cloud.positions[i]);
      c.farthest = std::max(c.farthest, d);
      c.apart += d > 0;
      const bool apart = glm::dot(w.normals[k], in_core.cloud.normals[i]) < 0;
      c.facing_apart += apart;
      c.facing_apart_on += apart && on(in_core.cloud.positions[i]) && in_core.status[i] == ProjectionStatus::converged;
      c.status_differ += w.status[k] != in_core.status[i];
    }
    next += w.positions.size();
  });
  EXPECT_EQ(next, in_core.cloud.size());
  return c;
}

// The file's cloud projected in core onto `surface` with adaptive widths, and the parameters.
std::pair<ProjectionParams, CloudProjection> projected_in_core(const std::string& file, SurfaceOperator surface) {
  ProjectionParams params = ProjectionParams::from_h(test::suggested_h(read_point_cloud(file)));
  params.support = Support::adaptive;
  params.surface = surface;
  Stats stats;
  return {params, project_cloud(read_point_cloud(file), params, Backend::cpu, stats)};
}

// A noisy torus and a sphere apart from it, with strays between: the torus crosses many tiles,
// each orienting its piece from its own highest point, and the sphere is a part of its own.
std::vector<vec3> torus_and_sphere_apart() {
  test::SampleOptions o;
  o.count = 20000;
  o.noise = 0.004f;
  std::vector<vec3> points = test::sample(test::Torus{}, o).positions;
  o.count = 3000;
  for (const vec3& p : test::sample(test::Sphere{vec3(3, 0, 0.5f), 0.5f}, o).positions) points.push_back(p);
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> across(-1.5f, 1.5f);
  for (int i = 0; i < 60; ++i) points.push_back(vec3(across(rng), across(rng), across(rng) * 0.5f));
  return points;
}

TEST_F(TiledProjectTest, ATorusAndASphereApartProjectInTilesAsInCore) {
  const std::vector<vec3> points = torus_and_sphere_apart();
  const std::string file = write("torus.xyz", test::xyz_text(points));
  PointCloud cloud = read_point_cloud(file);
  const float h = test::suggested_h(cloud);
  ProjectionParams params = ProjectionParams::from_h(h);
  params.support = Support::adaptive;
  Stats stats;
  const CloudProjection in_core = project_cloud(std::move(cloud), params, Backend::cpu, stats);
  // Both face outward in core: two closed parts apart, each as its own points vote (a rule
  // that gave the smaller a side by the normals' sum of both turned the sphere inward).
  const test::Torus torus;
  const test::Sphere sphere{vec3(3, 0, 0.5f), 0.5f};
  std::size_t on_surface = 0, inward = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const vec3 p = in_core.cloud.positions[i], n = in_core.cloud.normals[i];
    if (std::abs(sphere.distance(p)) < 0.01f) ++on_surface, inward += glm::dot(n, sphere.normal(p)) < 0;
    else if (std::abs(torus.distance(p)) < 0.01f) ++on_surface, inward += glm::dot(n, torus.normal(p)) < 0;
  }
  EXPECT_GT(on_surface, 22000u);
  EXPECT_EQ(inward, 0u);
  for (const std::uint64_t per_tile : {600u, 2500u}) {
    SCOPED_TRACE(per_tile);
    const Compared c = compare(in_core, file, dir_, params, per_tile, 7001);
    EXPECT_GT(c.tiles, 8u);
    EXPECT_EQ(c.apart, 0u) << "points projected otherwise than in core, as far as " << c.farthest;
    EXPECT_EQ(c.status_differ, 0u);
    EXPECT_EQ(c.facing_apart, 0u) << "of " << points.size() << " normals face otherwise than in core";
  }
}

// APSS and RIMLS fit the samples' normals: each estimated in its tile at the sample's place,
// oriented over the tiles as MLS's projections' normals are (the torus's pieces agreeing
// across the seams), then fitted with the halo's samples' normals; as in core.
TEST_F(TiledProjectTest, ApssAndRimlsFitTheSamplesNormalsInTilesAsInCore) {
  const std::vector<vec3> points = torus_and_sphere_apart();
  const std::string file = write("torus.xyz", test::xyz_text(points));
  for (const SurfaceOperator surface : {SurfaceOperator::apss, SurfaceOperator::rimls}) {
    SCOPED_TRACE(int(surface));
    const auto [params, in_core] = projected_in_core(file, surface);
    ASSERT_EQ(in_core.normals, NormalsUsed::estimated);
    const Compared c = compare(in_core, file, dir_, params, 600, 7001);
    EXPECT_GT(c.tiles, 8u);
    EXPECT_EQ(c.apart, 0u) << "points projected otherwise than in core, as far as " << c.farthest;
    EXPECT_EQ(c.status_differ, 0u);
    EXPECT_EQ(c.facing_apart, 0u) << "of " << points.size() << " normals face otherwise than in core";
  }
}

// A noisy sphere with a fifth as many strays about it: the second outliers' pass keeps the
// first's threshold, as in core, though the strays set aside moved the distances' median. The
// strays' own projections are no surface's (most stop at the iteration cap, within the
// sphere or outside it), and their normals' signs follow trees through them that rounding
// changes; the sphere's converged points face as in core, outward: from these strays' seed
// the tree turned the sphere inward until each part faced as its points vote, in core and
// tile by tile (points/facing_vote.hpp).
TEST_F(TiledProjectTest, TheOutliersPassesSetAsideWhatTheyDoInCore) {
  const std::vector<vec3> points = test::noisy_sphere_with_strays(2400, 5, 9);
  const std::string file = write("sphere.xyz", test::xyz_text(points));
  ProjectionParams params = ProjectionParams::from_h(test::suggested_h(read_point_cloud(file)));
  params.support = Support::adaptive;
  Stats stats;
  const CloudProjection in_core = project_cloud(read_point_cloud(file), params, Backend::cpu, stats);
  EXPECT_GT(in_core.outliers.set_aside, 200);
  std::size_t inward = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const vec3 p = in_core.cloud.positions[i];
    inward += std::abs(glm::length(p) - 1) < 0.05f && in_core.status[i] == ProjectionStatus::converged &&
              glm::dot(p, in_core.cloud.normals[i]) < 0;
  }
  EXPECT_EQ(inward, 0u);
  const Compared c = compare(in_core, file, dir_, params, 1500, 5000,
                             [](vec3 p) { return std::abs(glm::length(p) - 1) < 0.05f; });
  EXPECT_GT(c.tiles, 8u);
  EXPECT_EQ(c.apart, 0u) << "points projected otherwise than in core, as far as " << c.farthest;
  EXPECT_EQ(c.status_differ, 0u);
  EXPECT_EQ(c.facing_apart_on, 0u);
}

// A torus with noise of 2 spacings, whose supports would hold over 400 samples: merged
// (points/merged_samples.hpp) in each tile as in core, every cube whole in the tile that
// measures or uses its sample, summed in the points' order; strays 5σ out set aside by the
// threshold that weighs the merged samples' masses, as in core; with MLS and with RIMLS.
TEST_F(TiledProjectTest, ANoisyTorusMergesItsSamplesInTilesAsInCore) {
  test::SampleOptions o;
  o.count = 20000;
  o.noise = 0.05f;
  const test::Torus torus;
  std::vector<vec3> points = test::sample(torus, o).positions;
  for (int i = 0; i < 30; ++i) {
    const float u = 0.21f * float(i), v = 0.37f * float(i);
    const vec3 on(std::cos(u) * (torus.major + torus.minor * std::cos(v)),
                  std::sin(u) * (torus.major + torus.minor * std::cos(v)), torus.minor * std::sin(v));
    points.push_back(on + 5 * o.noise * torus.normal(on));
  }
  const std::string file = write("noisy.xyz", test::xyz_text(points));
  // RIMLS's samples' normals are fitted at the merged samples' places, the cubes' means.
  for (const SurfaceOperator surface : {SurfaceOperator::mls, SurfaceOperator::rimls}) {
    SCOPED_TRACE(int(surface));
    const auto [params, in_core] = projected_in_core(file, surface);
    ASSERT_GT(in_core.widths.merged_count, std::int64_t(points.size() / 2));
    EXPECT_GE(in_core.outliers.set_aside, 30);
    const Compared c = compare(in_core, file, dir_, params, 2500, 7001);
    EXPECT_GT(c.tiles, 8u);
    EXPECT_EQ(c.apart, 0u) << "points projected otherwise than in core, as far as " << c.farthest;
    EXPECT_EQ(c.status_differ, 0u);
    EXPECT_EQ(c.facing_apart, 0u) << "of " << points.size() << " normals face otherwise than in core";
  }
}

// The dragon's samples' normals under RIMLS: the orientation's tree crosses a thin fold whose
// plane fits straddle both walls. The rays (points/visibility.hpp) turn back what it turned,
// and the seams' turn (points/seam_turn.hpp) mends what seams are left, in core and tile by
// tile. The tiles' trees cross the fold elsewhere than the in-core tree (their pieces grown
// from each tile's highest point), but the rays see the same sides: against the scan's faces
// both are right but for 2 %, and they face alike but for a few. Without the rays in tiles,
// 9.6 % faced against the faces; without the seams' turn too, 32 %.
TEST_F(TiledProjectTest, TheSeamsTurnMendsARealScanInTilesAsInCore) {
  const std::string dragon = PSS_SOURCE_DIR "/../shared/data/dragon_21790.ply";
  if (!std::filesystem::exists(dragon)) GTEST_SKIP() << "no " << dragon;
  const auto [params, in_core] = projected_in_core(dragon, SurfaceOperator::rimls);
  ASSERT_EQ(in_core.normals, NormalsUsed::estimated);
  const test::ScanMesh scan = test::read_scan_mesh(dragon);
  ASSERT_EQ(scan.normals.size(), in_core.cloud.size());
  const auto against_the_scan = [&](std::size_t i, vec3 n) { return glm::dot(scan.normals[i], glm::dvec3(n)) < 0; };
  std::size_t in_core_against = 0;
  for (std::size_t i = 0; i < scan.normals.size(); ++i)
    in_core_against += against_the_scan(i, in_core.cloud.normals[i]);
  Stats stats;
  const TiledCloud tiles(dragon, dir_, 3000, 1 << 16);
  ASSERT_GT(tiles.tiles(), 6);
  const TiledProjection tiled(tiles, params, Backend::cpu, dir_, 7001, 1 << 16, stats);
  std::size_t tiles_against = 0, apart = 0;
  tiled.read_in_order([&](const ProjectedWindow& w) {
    for (std::size_t k = 0; k < w.normals.size(); ++k) {
      tiles_against += against_the_scan(w.first + k, w.normals[k]);
      apart += glm::dot(w.normals[k], in_core.cloud.normals[w.first + k]) < 0;
    }
  });
  const std::size_t n = scan.normals.size();
  EXPECT_LT(in_core_against, n * 4 / 100);
  EXPECT_LT(tiles_against, n * 4 / 100);  // without the rays tile by tile, 2,083
  EXPECT_LT(apart, n / 200);                // 25
}

// Pieces 0-1-2 one part, 3-4 another: the strongest votes join them, a weaker vote against
// them is outvoted, and each part keeps the sign of its piece grown from its highest point.
TEST(PieceSigns, TheStrongestVotesJoinPiecesAndTheHighestPieceKeepsItsSign) {
  PieceSigns signs;
  std::uint64_t root = 10;
  for (const float z : {0.1f, 0.9f, 0.5f, 0.3f, 0.3f}) signs.add_piece(z, root++, {});
  for (int k = 0; k < 5; ++k) signs.vote(0, 1, false);  // 0 and 1 face apart
  for (int k = 0; k < 4; ++k) signs.vote(2, 1, true);
  for (int k = 0; k < 3; ++k) signs.vote(0, 2, true);  // outvoted: 0 is apart from 1, so from 2
  signs.vote(4, 3, false);
  EXPECT_EQ(signs.turns().flip, (std::vector<char>{1, 0, 0, 0, 1}));  // 3 ties 4 in height: the lower index keeps
}

// A sphere's cap (the highest piece), its normals inward, and the rest, outward, facing apart
// where they meet: joined, the part faces as the rest's many normals vote, each piece's vote
// taken with its turn, so the cap turns and the rest stays.
TEST(PieceSigns, EachPartFacesAsItsPiecesVoteWithTheirTurns) {
  FacingVote cap, rest;
  for (int i = 0; i < 4000; ++i) {
    const float z = 1 - 2 * (float(i) + 0.5f) / 4000, r = std::sqrt(1 - z * z), a = float(i) * 2.39996323f;
    const vec3 p(r * std::cos(a), r * std::sin(a), z);
    if (z > 0.9f) cap.add(p, -p, 1.0f / (0.05f * 0.05f), ProjectionStatus::converged);
    else rest.add(p, p, 1.0f / (0.05f * 0.05f), ProjectionStatus::converged);
  }
  PieceSigns signs;
  signs.add_piece(1.0f, 0, cap);
  signs.add_piece(0.9f, 1, rest);
  signs.vote(0, 1, false);
  EXPECT_EQ(signs.turns().flip, (std::vector<char>{1, 0}));
}

TEST(PieceSigns, TiesInHeightGoByTheRootsIndex) {
  PieceSigns signs;
  signs.add_piece(0.3f, 7, {});
  signs.add_piece(0.3f, 2, {});
  signs.vote(0, 1, false);
  EXPECT_EQ(signs.turns().flip, (std::vector<char>{1, 0}));
  PieceSigns alone;
  alone.add_piece(0.0f, 0, {});
  EXPECT_EQ(alone.turns().flip, (std::vector<char>{0}));
}

// Pieces 0 and 1 share five points, alike by their trees' signs, which the rays' signs turn in
// piece 0 alone. Where the rays decide the part (a quarter of its samples vote, and 32), both
// pieces take the rays' signs, are joined apart by them, and the part faces as the rays' votes
// sum, over its heights (where they sum to nothing, as its heights with the rays' signs vote);
// where they do not decide, the trees' signs and the heights decide.
TEST(PieceSigns, WhereTheRaysDecideAPartTakesTheirSignsAndFacesAsTheyVote) {
  FacingVote up;  // a level patch facing up: its heights say the part faces as oriented
  for (int i = 0; i < 100; ++i)
    up.add(vec3(float(i % 10), float(i / 10), 0.0f), vec3(0, 0, 1), 1.0f, ProjectionStatus::converged);
  ASSERT_EQ(up.sign(), 1);
  const auto turns = [&](std::int64_t voters, std::int64_t seen0, std::int64_t seen1, const FacingVote& facing0) {
    PieceSigns signs;
    signs.add_piece(1.0f, 0, up, {100, voters, seen0, facing0});
    signs.add_piece(0.0f, 1, {}, {100, voters, seen1, {}});
    for (int k = 0; k < 5; ++k) signs.vote(0, 1, true, true, false);
    return signs.turns();
  };
  const PieceTurns decided = turns(25, 20, -20, up);
  EXPECT_EQ(decided.seen, (std::vector<char>{1, 1}));
  EXPECT_EQ(decided.flip, (std::vector<char>{0, 1}));
  EXPECT_TRUE(decided(0, true)) << "a point the rays' signs turn";
  EXPECT_FALSE(decided(0, false));
  EXPECT_EQ(turns(25, -30, 10, up).flip, (std::vector<char>{1, 0})) << "the rays outvote the heights";
  EXPECT_EQ(turns(25, 10, -30, up).flip, (std::vector<char>{0, 1})) << "piece 1's votes count with its turn";
  FacingVote down;  // piece 0's heights with the rays' signs, where their votes sum to nothing
  down.add(up, true);
  EXPECT_EQ(turns(25, 0, 0, down).flip, (std::vector<char>{1, 0}));
  const PieceTurns undecided = turns(10, -30, 10, up);  // 20 of 200 vote
  EXPECT_EQ(undecided.seen, (std::vector<char>{0, 0}));
  EXPECT_EQ(undecided.flip, (std::vector<char>{0, 0}));
  EXPECT_FALSE(undecided(0, true));
}

// Points with normals as XYZ text: six columns.
std::string xyz_with_normals(const std::vector<vec3>& points, const std::vector<vec3>& normals) {
  std::string text;
  char line[200];
  for (std::size_t i = 0; i < points.size(); ++i) {
    const vec3 p = points[i], n = normals[i];
    std::snprintf(line, sizeof line, "%.9g %.9g %.9g %.9g %.9g %.9g\n", double(p.x), double(p.y), double(p.z),
                  double(n.x), double(n.y), double(n.z));
    text += line;
  }
  return text;
}

// A file's normals tile by tile, as in core: each tile's own samples' (a merged sample's the
// mean of its cube's, summed in the cloud's order), checked against their neighbours' planes,
// their seams turned over the tiles (the torus's far half flipped), then fitted by RIMLS and
// orienting MLS's projections, strays set aside with a hint from their nearest sample; and a
// torus noisy enough that its samples merge. The same points and normals, to the last bit.
TEST_F(TiledProjectTest, AFilesNormalsProjectInTilesAsInCore) {
  const test::Torus torus;
  const test::Sphere sphere{vec3(3, 0, 0.5f), 0.5f};
  // The surfaces' own normals (the strays' random), those beyond x = `flip_beyond` flipped.
  const auto normals_of = [&](const std::vector<vec3>& points, float flip_beyond, float stray_beyond) {
    std::vector<vec3> normals;
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> any(-1, 1);
    for (const vec3& p : points) {
      vec3 n = std::abs(sphere.distance(p)) < 0.05f ? sphere.normal(p) : torus.normal(p);
      if (std::abs(sphere.distance(p)) >= stray_beyond && std::abs(torus.distance(p)) >= stray_beyond)
        n = vec3(any(rng), any(rng), 1);
      normals.push_back(p.x > flip_beyond ? -n : n);
    }
    return normals;
  };
  const std::vector<vec3> apart = torus_and_sphere_apart();
  test::SampleOptions o;
  o.count = 20000;
  o.noise = 0.05f;
  const std::vector<vec3> noisy = test::sample(torus, o).positions;
  const std::string files[] = {write("apart.xyz", xyz_with_normals(apart, normals_of(apart, 0.3f, 0.05f))),
                               write("noisy.xyz", xyz_with_normals(noisy, normals_of(noisy, kInfinity, kInfinity)))};
  for (const std::string& file : files)
    for (const SurfaceOperator surface : {SurfaceOperator::mls, SurfaceOperator::rimls}) {
      SCOPED_TRACE(file + " " + std::to_string(int(surface)));
      const auto [params, in_core] = projected_in_core(file, surface);
      ASSERT_EQ(in_core.normals, surface == SurfaceOperator::mls ? NormalsUsed::none : NormalsUsed::file);
      EXPECT_GT(in_core.outliers.set_aside, 0);
      if (file == files[0]) EXPECT_GT(in_core.normals_turned, 2000u);
      if (file == files[1]) EXPECT_GT(in_core.widths.merged_count, 10000);
      Stats stats;
      const TiledCloud tiles(file, dir_, 2500, 1 << 16);
      const TiledProjection tiled(tiles, params, Backend::cpu, dir_, 7001, 1 << 16, stats);
      EXPECT_EQ(tiled.normals_turned(), in_core.normals_turned);
      EXPECT_EQ(tiled.file_normals_off(), 0u);
      const Compared c = compare(in_core, file, dir_, params, 2500, 7001);
      EXPECT_GT(c.tiles, 8u);
      EXPECT_EQ(c.apart, 0u) << "points projected otherwise than in core, as far as " << c.farthest;
      EXPECT_EQ(c.status_differ, 0u);
      EXPECT_EQ(c.facing_apart, 0u) << "normals face otherwise than in core";
    }
}

// A noisy torus (noise about 2 spacings) whose file's normals face in on its half x > 0: the
// seams' turn, its patches fragmented by the noise, leaves much of that half inward, and the
// rays (points/visibility.hpp: face_file_normals_as_seen) see it facing in and turn it, in
// core and tile by tile (without the rays in tiles, half the torus stayed inward). Beside it a
// clean sphere, its half x > 3 flipped, which the seams' turn mends before the rays: the
// summary counts the normals both turned, once each.
TEST_F(TiledProjectTest, ANoisyFilesFlippedHalfIsTurnedInTilesAsInCore) {
  const test::Torus torus;
  const test::Sphere sphere{vec3(3, 0, 0.5f), 0.5f};
  test::SampleOptions o;
  o.count = 20000;
  o.noise = 0.05f;
  std::vector<vec3> points = test::sample(torus, o).positions;
  const std::size_t on_torus = points.size();
  o.count = 3000;
  o.noise = 0;
  for (const vec3& p : test::sample(sphere, o).positions) points.push_back(p);
  const auto truth = [&](std::size_t i) { return i < on_torus ? torus.normal(points[i]) : sphere.normal(points[i]); };
  std::vector<vec3> normals;
  std::size_t flipped = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const bool flip = i < on_torus ? points[i].x > 0 : points[i].x > 3;
    normals.push_back(flip ? -truth(i) : truth(i));
    flipped += flip;
  }
  const std::string file = write("flipped.xyz", xyz_with_normals(points, normals));
  const auto [params, in_core] = projected_in_core(file, SurfaceOperator::rimls);
  ASSERT_EQ(in_core.normals, NormalsUsed::file);
  std::size_t in_core_inward = 0;
  for (std::size_t i = 0; i < points.size(); ++i) in_core_inward += glm::dot(in_core.cloud.normals[i], truth(i)) < 0;
  Stats stats;
  const TiledCloud tiles(file, dir_, 2500, 1 << 16);
  ASSERT_GT(tiles.tiles(), 6);
  const TiledProjection tiled(tiles, params, Backend::cpu, dir_, 7001, 1 << 16, stats);
  std::size_t tiles_inward = 0;
  tiled.read_in_order([&](const ProjectedWindow& w) {
    for (std::size_t k = 0; k < w.normals.size(); ++k) tiles_inward += glm::dot(w.normals[k], truth(w.first + k)) < 0;
  });
  EXPECT_LT(in_core_inward, points.size() / 100);  // 0
  EXPECT_LT(tiles_inward, points.size() / 100);    // 0
  // Samples turned: fewer than the points flipped, where the torus's merge.
  EXPECT_GT(in_core.normals_turned, flipped / 3);
  EXPECT_LE(in_core.normals_turned, flipped);
  EXPECT_NEAR(double(tiled.normals_turned()), double(in_core.normals_turned), 0.001 * double(points.size()));
}

// Normals that do not follow the points (random) are left out in tiles as in core, and
// estimated; so are all of a file that gives a sample no direction.
TEST_F(TiledProjectTest, AFilesNormalsLeftOutInCoreAreLeftOutInTiles) {
  test::SampleOptions o;
  o.count = 6000;
  const std::vector<vec3> points = test::sample(test::Sphere{}, o).positions;
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> any(-1, 1);
  std::vector<vec3> random(points.size()), one_zero(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    random[i] = vec3(any(rng), any(rng), any(rng));
    one_zero[i] = i == 77 ? vec3(0.0f) : points[i];
  }
  const std::string files[] = {write("random.xyz", xyz_with_normals(points, random)),
                               write("zero.xyz", xyz_with_normals(points, one_zero))};
  for (const std::string& file : files) {
    SCOPED_TRACE(file);
    const auto [params, in_core] = projected_in_core(file, SurfaceOperator::rimls);
    ASSERT_EQ(in_core.normals, NormalsUsed::estimated);
    Stats stats;
    const TiledCloud tiles(file, dir_, 700, 1 << 16);
    const TiledProjection tiled(tiles, params, Backend::cpu, dir_, 7001, 1 << 16, stats);
    EXPECT_EQ(tiled.file_normals_off(), in_core.file_normals_off);
    EXPECT_EQ(tiled.normals_without_direction(), file == files[1] ? 1u : 0u);
    const Compared c = compare(in_core, file, dir_, params, 700, 7001);
    EXPECT_GT(c.tiles, 6u);
    EXPECT_EQ(c.apart, 0u);
    EXPECT_EQ(c.facing_apart, 0u);
  }
  const auto [params, in_core] = projected_in_core(files[0], SurfaceOperator::rimls);
  EXPECT_GT(in_core.file_normals_off, points.size() / 2);
}

}  // namespace
}  // namespace pss
