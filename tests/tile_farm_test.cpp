// The tiles' farm (tiles/farm.hpp, issue 28): a tile's work is a pure function of its
// request's bytes, so that a farm that works the tiles elsewhere and in another order, as
// mpirun's ranks do, gives the local farm's result bit for bit, and each rank's points are
// counted; a request that does not hold together is an error, not a read past its end.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <vector>

#include "../src/tiles/tile_bytes.hpp"
#include "../src/tiles/tile_works.hpp"
#include "pss/core/error.hpp"
#include "pss/io/point_cloud_file.hpp"
#include "pss/tiles/farm.hpp"
#include "pss/tiles/project.hpp"
#include "support/cli.hpp"
#include "support/file_bytes.hpp"
#include "support/shapes.hpp"

namespace pss {
namespace {

using TileFarmTest = test::CliTest;

// Works every tile on a copy of its request, the last tile first; tile t on rank t % 3.
class Elsewhere final : public TileFarm {
 public:
  int ranks() const override { return 3; }
  void run(TileStep step, std::span<const int> tiles, const Request& request, const Take& take) override {
    std::vector<std::vector<std::byte>> results(tiles.size()), notes(tiles.size());
    for (std::size_t k = tiles.size(); k-- > 0;) {
      const TileRequest copy = request(tiles[k]);
      results[k] = tile_work(step, copy.work);
      notes[k] = copy.notes;
    }
    for (std::size_t k = 0; k < tiles.size(); ++k) take(tiles[k], results[k], notes[k], tiles[k] % 3);
  }
};

TEST_F(TileFarmTest, TilesWorkedElsewhereInAnotherOrderGiveTheSameBitsAndCountEachRanksPoints) {
  const std::vector<vec3> points = test::noisy_sphere_with_strays(600, 11, 7);
  const std::string file = write("sphere.xyz", test::xyz_text(points));
  ProjectionParams params = ProjectionParams::from_h(test::suggested_h(read_point_cloud(file)));
  params.support = Support::adaptive;
  const TiledCloud tiles(file, dir_, 1500, 1 << 16);
  ASSERT_GT(tiles.tiles(), 6);
  Stats stats;
  Elsewhere elsewhere;
  const TiledProjection local(tiles, params, Backend::cpu, dir_, 5000, 1 << 16, stats, local_farm());
  const TiledProjection farmed(tiles, params, Backend::cpu, dir_, 5000, 1 << 16, stats, elsewhere);
  EXPECT_GT(local.outliers().set_aside, 20);
  EXPECT_EQ(farmed.outliers().set_aside, local.outliers().set_aside);
  EXPECT_EQ(farmed.outliers().threshold, local.outliers().threshold);

  std::vector<ProjectedWindow> expected;
  local.read_in_order([&](ProjectedWindow& w) { expected.push_back(std::move(w)); });
  std::size_t window = 0;
  farmed.read_in_order([&](const ProjectedWindow& w) {
    ASSERT_LT(window, expected.size());
    const ProjectedWindow& e = expected[window++];
    ASSERT_EQ(w.first, e.first);
    ASSERT_EQ(w.positions.size(), e.positions.size());
    EXPECT_EQ(std::memcmp(w.positions.data(), e.positions.data(), w.positions.size() * sizeof(vec3)), 0);
    EXPECT_EQ(std::memcmp(w.normals.data(), e.normals.data(), w.normals.size() * sizeof(vec3)), 0);
    EXPECT_EQ(w.status, e.status);
  });
  EXPECT_EQ(window, expected.size());

  ASSERT_EQ(local.points_per_rank(), std::vector<std::uint64_t>{points.size()});
  std::vector<std::uint64_t> per_rank(3, 0);
  for (int t = 0; t < tiles.tiles(); ++t) per_rank[std::size_t(t % 3)] += tiles.tile_size(t);
  EXPECT_EQ(farmed.points_per_rank(), per_rank);
}

// Four samples 0.01 apart, each 0.01 wide, two of them the tile's own, and their layout.
struct FourSamples {
  explicit FourSamples(float lift) : unit{{0, 0, 0}, {0.01f, 0, 0}, {0, 0.01f, 0}, {0.01f, 0.01f, lift}} {
    SupportTally tally;
    tally.least = 0.01f;
    for (const vec3& p : unit) tally.add(p, 0.01f);
    layout = support_layout(tally, 2);
  }
  UnitTile tile(std::span<const vec3> normals = {}) const { return {unit, h, samples, 2, {}, {}, normals, &layout}; }
  std::vector<vec3> unit;
  std::vector<float> h = std::vector<float>(4, 0.01f);
  std::vector<int> samples = {0, 1, 2, 3};
  SupportLayout layout;
};

TEST(TileWork, ARequestCutShortOrOfNoStepIsAnError) {
  const FourSamples four(0.001f);
  const std::vector<vec3>& unit = four.unit;
  const std::vector<float>& h = four.h;
  const std::vector<int>& samples = four.samples;
  const SupportLayout& layout = four.layout;
  const UnitTile tile = four.tile();
  EXPECT_THROW(outliers_request(UnitTile{unit, h, samples, 2}), Error) << "no layout";
  const std::vector<std::byte> outliers = outliers_request(tile);
  const std::vector<std::byte> projection = projection_request(tile, ProjectionParams::from_h(0.01f), Backend::cpu);
  const std::vector<vec3> normals(unit.size(), vec3(0, 0, 1));
  const std::vector<float> radius(unit.size(), 0.02f);
  const std::vector<std::uint64_t> id = {5, 6, 7, 8};
  const Occupancy occupancy(unit, normals, radius);
  const std::vector<std::byte> orientation = orientation_request(unit, normals, radius, id, occupancy);
  EXPECT_EQ(outliers_result(tile_work(TileStep::outliers, outliers)).distance.size(), 2u);
  // Merged samples: a cube's first point out of the set is refused, not followed.
  const std::vector<int> into = {0, 0, 2, 9};
  const UnitTile merged{unit, h, samples, 2, unit, into, {}, &layout};
  EXPECT_THROW(tile_work(TileStep::outliers, outliers_request(merged)), Error);
  EXPECT_EQ(projection_result(tile_work(TileStep::projection, projection)).projected.size(), 2u);
  EXPECT_EQ(orientation_result(tile_work(TileStep::orientation, orientation), 4).parts.of_point.size(), 4u);
  EXPECT_THROW(orientation_result(tile_work(TileStep::orientation, orientation), 5), Error);
  const MarginTile whole{unit, id, {}, 2, 9, 1.0};  // the cloud's indices 5 to 8 of 9
  const std::vector<std::byte> spacing = spacing_request(whole, 1);
  const std::vector<float> spacings(unit.size(), 0.01f), noise_measured = {0.0f};
  const std::vector<vec3> noise_at = {unit[0]};
  const std::vector<std::byte> widths =
      widths_request(whole, {spacings, spacings, 0.01f, 0.01f, 0.04f, 2.0f, noise_at, noise_measured});
  EXPECT_FALSE(spacing_result(tile_work(TileStep::spacing, spacing), 2).complete) << "4 points hold no 16 neighbours";
  const TileWidths w = widths_result(tile_work(TileStep::widths, widths), 2);
  EXPECT_TRUE(w.complete);
  EXPECT_EQ(w.h.size(), 2u);
  EXPECT_THROW(tile_work(TileStep::spacing, spacing_request({unit, id, {}, 2, 8, 1.0}, 1)), Error)
      << "an index past the cloud's size";
  // The file's normals: each own sample's, and a point's whose set lacks its index refused.
  const std::vector<vec3> up(unit.size(), vec3(0, 0, 1));
  const std::vector<std::byte> file_normals = file_normals_request(tile, up, id);
  const TileFileNormals f = file_normals_result(tile_work(TileStep::file_normals, file_normals));
  EXPECT_EQ(f.sample, (std::vector<int>{0, 1}));
  EXPECT_EQ(f.normal, (std::vector<vec3>(2, vec3(0, 0, 1))));
  EXPECT_THROW(tile_work(TileStep::file_normals, file_normals_request(tile, up, {})), Error);
  const std::pair<TileStep, const std::vector<std::byte>*> requests[] = {
      {TileStep::outliers, &outliers}, {TileStep::projection, &projection}, {TileStep::orientation, &orientation},
      {TileStep::spacing, &spacing},   {TileStep::widths, &widths},         {TileStep::file_normals, &file_normals}};
  for (const auto& [step, request] : requests)
    for (const std::size_t cut : {std::size_t(0), std::size_t(3), request->size() / 2, request->size() - 1}) {
      const std::span<const std::byte> part(request->data(), cut);
      EXPECT_THROW(tile_work(step, part), Error) << int(step) << " cut at " << cut;
    }
  EXPECT_THROW(tile_work(TileStep(99), projection), Error);
  // An array's length past the request's end fails before anything that long is made.
  const std::size_t head = sizeof(SupportLayout) + sizeof(std::uint64_t);  // the layout and the own count
  std::vector<std::byte> lying(outliers.begin(), outliers.begin() + std::ptrdiff_t(head));
  const std::uint64_t huge = std::uint64_t(1) << 61;
  lying.resize(lying.size() + sizeof huge);
  std::memcpy(lying.data() + head, &huge, sizeof huge);
  EXPECT_THROW(tile_work(TileStep::outliers, lying), Error);
  // A sample that is not in the tile.
  const std::vector<int> beyond = {0, 4};
  EXPECT_THROW(tile_work(TileStep::outliers, outliers_request({unit, h, beyond, 2, {}, {}, {}, &layout})), Error);
}

// The seams' turn's three steps (seam_turn_work.cpp): each needs the samples' normals, and
// its patches or their settling for each point of the set; a step past the three, a request
// cut short and a result whose arrays disagree are errors.
TEST(TileWork, TheSeamsTurnsStepsNeedTheirArrays) {
  const FourSamples four(0.0f);
  const std::vector<vec3> normals = {{0, 0, 1}, {0, 0, 1}, {0, 0, -1}, {0, 0, -1}};
  const UnitTile tile = four.tile(normals);
  const std::vector<std::uint32_t> patch = {0, 0, 1, 1};
  const std::vector<char> settled = {0, 1, 1, 1};
  const TileSeamTurn joins =
      seam_turn_result(tile_work(TileStep::seam_turn, seam_turn_request(tile, SeamStep::joins)), SeamStep::joins);
  EXPECT_EQ(joins.joined, std::vector<int>{1}) << "own samples 0 and 1 agree side by side; 2 and 3 are no own";
  EXPECT_EQ(joins.root, std::vector<int>{0});
  const std::vector<std::byte> evidence = seam_turn_request(tile, SeamStep::evidence, patch);
  const TileSeamTurn seen = seam_turn_result(tile_work(TileStep::seam_turn, evidence), SeamStep::evidence);
  ASSERT_EQ(seen.evidence.size(), 1u);
  EXPECT_EQ(seen.evidence.begin()->first, std::uint64_t(1)) << "patches 0 and 1";
  const TileSeamTurn says = seam_turn_result(
      tile_work(TileStep::seam_turn, seam_turn_request(tile, SeamStep::stragglers, {}, settled)), SeamStep::stragglers);
  EXPECT_EQ(says.straggler, std::vector<int>{0}) << "own sample 1 is settled";
  EXPECT_THROW(tile_work(TileStep::seam_turn, seam_turn_request(four.tile(), SeamStep::joins)), Error);
  EXPECT_THROW(tile_work(TileStep::seam_turn, seam_turn_request(tile, SeamStep::evidence)), Error) << "no patches";
  EXPECT_THROW(tile_work(TileStep::seam_turn, seam_turn_request(tile, SeamStep::stragglers)), Error) << "no settling";
  EXPECT_THROW(tile_work(TileStep::seam_turn, seam_turn_request(tile, SeamStep(3))), Error);
  for (const std::size_t cut : {std::size_t(0), evidence.size() / 2, evidence.size() - 1})
    EXPECT_THROW(tile_work(TileStep::seam_turn, std::span<const std::byte>(evidence.data(), cut)), Error) << cut;
  ByteWriter uneven;
  uneven.put_array<int>(std::vector<int>{1, 2});
  uneven.put_array<int>(std::vector<int>{0});
  EXPECT_THROW(seam_turn_result(uneven.take(), SeamStep::joins), Error);
}

// A tile's piece of a mesh (mesh_work.cpp) that does not hold together is an error, not a
// vertex read past its arrays.
TEST(TileWork, AMeshPieceThatDoesNotHoldTogetherIsAnError) {
  const auto piece = [](std::size_t keys, int corner) {
    ByteWriter out;
    out.put(MarchCounts{});
    out.put_array<std::uint64_t>(std::vector<std::uint64_t>(keys, 9));
    const std::vector<vec3> three(3, vec3(0));
    out.put_array<vec3>(three);  // positions
    out.put_array<vec3>(three);  // normals
    out.put_array<float>(std::vector<float>(3, 1.0f));
    out.put_array<std::array<int, 3>>(std::vector<std::array<int, 3>>{{0, 1, corner}});
    out.put_array<std::uint64_t>(std::vector<std::uint64_t>{1});
    out.put_array<std::int32_t>(std::vector<std::int32_t>{0});
    return out.take();
  };
  EXPECT_EQ(mesh_result(piece(3, 2)).piece.mesh.triangles.size(), 1u);
  EXPECT_THROW(mesh_result(piece(2, 2)), Error) << "a key for each vertex";
  EXPECT_THROW(mesh_result(piece(3, 3)), Error) << "a triangle's corner past the vertices";
}

// A sphere whose normals face out above z = 0.15, in below z = −0.15, and turn smoothly in the
// band between, so that a tile's tree carries their signs through the band and its lower cap
// faces in. The tile's work gives the tree's signs and turns where the rays say otherwise: the
// lower cap, whose rays along its normals all meet the sphere's far side. Each point's vote is
// given as its normal faces after that turn, and a point that follows a merged sample takes
// its sample's turn and casts no vote.
TEST(TileWork, TheRaysTurnWhatATreeCarriedInwardAndSayHowTheyVote) {
  const int count = 4000;
  std::vector<vec3> points, normals;
  for (int i = 0; i < count; ++i) {  // a Fibonacci sphere
    const float z = 1 - 2 * (float(i) + 0.5f) / float(count), r = std::sqrt(1 - z * z), a = float(i) * 2.39996323f;
    const vec3 p(r * std::cos(a), r * std::sin(a), z);
    const float turn = 3.14159265f * std::clamp((0.15f - z) / 0.3f, 0.0f, 1.0f);
    const vec3 up = glm::normalize(vec3(0, 0, 1) - z * p);  // along the meridian
    points.push_back(p);
    normals.push_back(std::cos(turn) * p + std::sin(turn) * up);
  }
  std::vector<int> sample(count, -1);
  for (int k = 0; k < 400; ++k) {  // points that follow a sample, one in ten
    points.push_back(points[std::size_t(10 * k)]);
    normals.push_back(normals[std::size_t(10 * k)]);
    sample.push_back(10 * k);
  }
  const std::vector<float> radius(points.size(), 0.2f);  // ρ: about 3.5 spacings
  std::vector<std::uint64_t> id(points.size());
  for (std::size_t i = 0; i < id.size(); ++i) id[i] = i;
  const std::span<const vec3> on_sphere = std::span<const vec3>(points).first(count);
  const std::vector<float> disc(count, 0.1f);  // ρ/2, as the tiles mark them
  const Occupancy occupancy(on_sphere, std::span<const vec3>(normals).first(count), disc);
  const TileOrientation o = orientation_result(
      tile_work(TileStep::orientation, orientation_request(points, normals, radius, id, occupancy, sample)),
      points.size());
  std::size_t cap = 0, carried_in = 0, seen_out = 0, followers_turned = 0;
  for (int i = 0; i < count; ++i) {
    const vec3 p = points[std::size_t(i)], n = o.normals[std::size_t(i)];
    if (p.z > -0.3f) continue;
    ++cap;
    carried_in += glm::dot(n, p) < 0;
    seen_out += glm::dot(o.seen_turned[std::size_t(i)] ? -n : n, p) > 0;
  }
  EXPECT_GT(cap, 1000u);
  EXPECT_EQ(carried_in, cap) << "the tree's signs";
  EXPECT_GT(seen_out, cap * 99 / 100) << "the rays' signs";
  // The votes as the rays' signs face: the votes along the tree's normals, turned with them.
  const std::vector<std::int8_t> along_tree =
      visibility_votes(occupancy, on_sphere, std::span<const vec3>(o.normals).first(count), disc);
  for (std::size_t i = 0; i < std::size_t(count); ++i)
    ASSERT_EQ(o.seen_votes[i], o.seen_turned[i] ? -along_tree[i] : along_tree[i]) << i;
  for (std::size_t i = count; i < points.size(); ++i) {
    const auto j = std::size_t(sample[i]);
    EXPECT_EQ(o.seen_turned[i], o.seen_turned[j]) << i;
    EXPECT_EQ(o.seen_votes[i], 0) << i;
    EXPECT_GT(glm::dot(o.normals[i], o.normals[j]), 0.0f) << i;
    followers_turned += o.seen_turned[i] != 0;
  }
  EXPECT_GT(followers_turned, 50u);
}

}  // namespace
}  // namespace pss
