// Adaptive support (issue 26): the samples' widths (points/support.hpp) against their
// definition, and the grid of per-sample supports (spatial/support_grid.hpp) against brute force.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>
#include <random>

#include "pss/core/error.hpp"
#include "pss/points/project_cloud.hpp"
#include "pss/points/render_cloud.hpp"
#include "pss/points/spacing.hpp"
#include "pss/points/support.hpp"
#include "pss/spatial/support_grid.hpp"
#include "support/shapes.hpp"

namespace pss {
namespace {

// A square grid of samples on z = 0, `a` apart for x ≥ 0 and `a·ratio` apart for x < 0:
// a step in spacing (the density falls by ratio²).
std::vector<vec3> stepped_plane(float a, float ratio) {
  std::vector<vec3> points;
  for (float x = 0; x <= 1; x += a)
    for (float y = 0; y <= 1; y += a) points.push_back(vec3(x, y, 0));
  for (float x = -a * ratio; x >= -1; x -= a * ratio)
    for (float y = 0; y <= 1; y += a * ratio) points.push_back(vec3(x, y, 0));
  return points;
}

float median_of(std::vector<float> v) {
  std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(v.size() / 2), v.end());
  return v[v.size() / 2];
}

TEST(SupportWidths, GlobalGivesEverySampleH) {
  const std::vector<vec3> points = stepped_plane(0.02f, 3);
  ProjectionParams params = ProjectionParams::from_h(0.05f);
  const SupportWidths w = support_widths(points, params);
  ASSERT_EQ(w.h.size(), points.size());
  for (float h : w.h) EXPECT_EQ(h, 0.05f);
  EXPECT_EQ(w.least, 0.05f);
  EXPECT_EQ(w.largest, 0.05f);
}

// On a grid the distance to the 15th neighbour is a fixed multiple of the spacing: the dense
// side keeps h, the sparse side (spacing ratio 3, away from the step) widens by 0.75·3.
TEST(SupportWidths, AdaptiveWidensWithTheSpacingWhereSparserThanTheMedian) {
  const float a = 0.01f, ratio = 3;
  const std::vector<vec3> points = stepped_plane(a, ratio);
  const float h = float(estimate_spacing(points).suggested_h);
  ProjectionParams params = ProjectionParams::from_h(h);
  params.support = Support::adaptive;
  const SupportWidths w = support_widths(points, params);
  std::vector<float> dense, sparse;
  for (std::size_t i = 0; i < points.size(); ++i) {
    EXPECT_GE(w.h[i], h);
    const float x = points[i].x;
    if (x > 0.2f && x < 0.8f) dense.push_back(w.h[i]);
    if (x < -0.2f && x > -0.8f && points[i].y > 0.2f && points[i].y < 0.8f) sparse.push_back(w.h[i]);
  }
  ASSERT_GT(sparse.size(), 100u);
  EXPECT_EQ(median_of(dense), h);
  EXPECT_NEAR(median_of(sparse), kSupportWidening * ratio * h, 0.1 * kSupportWidening * ratio * h);
  EXPECT_EQ(w.least, h);
  EXPECT_NEAR(w.largest, *std::max_element(w.h.begin(), w.h.end()), 0);
}

// A stray sample far off the plane: its own 15th neighbour is far, but its width is the median
// over its neighbourhood's, the plane's. So its support reaches no other sample: it neither
// bends the plane below it nor, with too few samples in reach, makes a surface of its own.
TEST(SupportWidths, AStraySampleTakesItsNeighboursWidthAndIsLeftOut) {
  std::vector<vec3> points = stepped_plane(0.02f, 1);
  points.push_back(vec3(0.5f, 0.5f, 0.4f));
  const float h = float(estimate_spacing(points).suggested_h);
  ProjectionParams params = ProjectionParams::from_h(h);
  params.support = Support::adaptive;
  const SupportWidths w = support_widths(points, params);
  EXPECT_LT(w.h.back(), 1.5f * h);
  PointCloud cloud;
  cloud.positions = points;
  RayPssParams ray = RayPssParams::from_h(h);
  ray.projection.support = Support::adaptive;
  ray.projection.outliers = OutlierPolicy::keep;  // the widths alone (outliers_test.cpp sets it aside)
  params.outliers = OutlierPolicy::keep;
  Stats stats;
  const PreparedCloud prepared(cloud, ray, Backend::cpu, stats);
  EXPECT_EQ(prepared.left_out(), 1);
  Stats project_stats;
  const CloudProjection projected = project_cloud(cloud, params, Backend::cpu, project_stats);
  for (std::size_t i = 0; i + 1 < points.size(); ++i) EXPECT_LT(std::abs(projected.cloud.positions[i].z), 1e-5f) << i;
}

// A small cluster apart from the rest (12 samples 0.02 apart, 0.5 above a plane sampled as
// finely): its 15th neighbours lie across the gap, but a 15th distance beyond twice the 8th is
// a gap, not spacing, so the cluster keeps about its own spacing's width, not the gap's (~8h),
// and does not swell into a disc.
TEST(SupportWidths, ASmallClusterApartKeepsItsOwnSpacing) {
  std::vector<vec3> points = stepped_plane(0.02f, 1);
  const std::size_t plane = points.size();
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 3; ++j) points.push_back(vec3(0.4f + 0.02f * float(i), 0.4f + 0.02f * float(j), 0.5f));
  const float h = float(estimate_spacing(points).suggested_h);
  ProjectionParams params = ProjectionParams::from_h(h);
  params.support = Support::adaptive;
  const SupportWidths w = support_widths(points, params);
  for (std::size_t i = plane; i < points.size(); ++i) EXPECT_LT(w.h[i], 2.5f * h) << i;
}

// A thin part where the cloud is sparse (a bunny's ear at 1/8 of the density): a tube 12
// samples round, 4 plane spacings apart, beside a dense plane. Its 32 nearest samples wrap
// round the tube and read as a volume; its 16 nearest, the neighbourhood its spacing is
// measured over, lie on a surface. Every sample of the tube widens.
TEST(SupportWidths, AThinTubeWhereTheCloudIsSparseWidens) {
  const float a = 0.01f, s = 4 * a;
  std::vector<vec3> points;
  for (float x = -1; x <= 1; x += a)
    for (float y = -1; y <= 1; y += a) points.push_back(vec3(x, y, -0.5f));
  const std::size_t plane = points.size();
  const int around = 12;
  const float radius = float(around) * s / (2 * std::numbers::pi_v<float>);
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> jitter(-0.05f * s, 0.05f * s);
  for (float x = -0.9f; x <= 0.9f; x += s)
    for (int k = 0; k < around; ++k) {
      const float angle = 2 * std::numbers::pi_v<float> * (float(k) + 0.5f * float(int(std::lround(x / s)) % 2)) / float(around);
      points.push_back(vec3(x + jitter(rng), radius * std::cos(angle), radius * std::sin(angle)));
    }
  const float h = float(estimate_spacing(points).suggested_h);
  ProjectionParams params = ProjectionParams::from_h(h);
  params.support = Support::adaptive;
  const SupportWidths w = support_widths(points, params);
  std::size_t tube = 0, wide = 0;
  for (std::size_t i = plane; i < points.size(); ++i) {
    if (std::abs(points[i].x) > 0.8f) continue;  // the tube's ends
    ++tube;
    wide += w.h[i] > 2 * h;
  }
  ASSERT_GT(tube, 400u);
  EXPECT_EQ(wide, tube);
}

// Outliers strewn through the box of a noisy sphere (1 %, as a scanner's strays) are sparse
// and each other's neighbours, but fill a volume, or sit next to the denser surface: none
// widens (each would make a sheet of its own), while the sparse half of a stepped sphere
// does (AdaptiveWidensWithTheSpacing..., render_test's DensitySteps).
TEST(SupportWidths, OutliersStrewnAroundASurfaceDoNotWiden) {
  for (const std::uint32_t seed : {1u, 2u, 3u, 4u}) {
    test::SampleOptions o;
    o.count = 20000;
    o.noise = 0.003f;
    o.seed = seed;
    std::vector<vec3> points = test::sample(test::Sphere{}, o).positions;
    const std::size_t surface = points.size();
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> coordinate(-1, 1);
    for (std::size_t i = 0; i < surface / 100 * seed / 2; ++i)  // 0.5 %, 1 %, 1.5 %, 2 %
      points.push_back(vec3(coordinate(rng), coordinate(rng), coordinate(rng)));
    const float h = float(estimate_spacing(points).suggested_h);
    ProjectionParams params = ProjectionParams::from_h(h);
    params.support = Support::adaptive;
    const SupportWidths w = support_widths(points, params);
    // A few strays among strays may read a little noise from six coefficients fitted to
    // their 16 nearest (1.04 h, three of 400 at seed 4): no sheet of their own.
    std::size_t widened = 0;
    for (std::size_t i = surface; i < points.size(); ++i) {
      widened += w.h[i] != h;
      EXPECT_LT(w.h[i], 1.1f * h) << "seed " << seed << ", outlier " << i;
    }
    EXPECT_LE(widened, (points.size() - surface) / 50) << "seed " << seed;
  }
}

// ρ_i = ρ·h_i/h stays within the cloud's bounding-box diagonal however sparse a sample's
// neighbourhood: here a row of 30 samples 0.03 apart leaving a dense patch would take
// h_i ≈ 0.75·h·0.24/0.005 ≈ 36h, and with ρ = 8h a ρ_i of 1.4 beyond the diagonal (0.99).
TEST(SupportWidths, NoSupportReachesBeyondTheCloud) {
  std::vector<vec3> points;
  for (int i = 0; i < 45; ++i)
    for (int j = 0; j < 45; ++j) points.push_back(vec3(0.002f * float(i), 0.002f * float(j), 0));
  for (int i = 1; i <= 30; ++i) points.push_back(vec3(0.09f + 0.03f * float(i), 0.045f, 0));
  ProjectionParams params = ProjectionParams::from_h(float(estimate_spacing(points).suggested_h));
  params.rho = 8 * params.h;
  params.support = Support::adaptive;
  Aabb box;
  for (const vec3& p : points) box.grow(p);
  const float diagonal = glm::length(box.extent());
  const SupportWidths w = support_widths(points, params);
  ASSERT_LT(diagonal, kSupportSpread * params.rho);  // the diagonal, not the spread, bounds them
  for (float h : w.h) EXPECT_LE(h * params.rho / params.h, 1.0001f * diagonal);
  EXPECT_GT(w.largest * params.rho / params.h, 0.99f * diagonal);
}

TEST(SupportWidths, RefusesAWidthThatIsNotPositive) {
  const std::vector<vec3> points = stepped_plane(0.1f, 1);
  for (float h : {0.0f, -1.0f, NAN, INFINITY}) {
    ProjectionParams params = ProjectionParams::from_h(h);
    params.support = Support::adaptive;
    EXPECT_THROW(support_widths(points, params), Error) << h;
  }
}

// Every query finds exactly the samples whose own support holds it, for widths spread 100:1
// over 8 levels and beyond (the last level takes the widest).
TEST(SupportGrid, CoveringQueriesEqualBruteForce) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  std::uniform_real_distribution<float> exponent(0.0f, 9.0f);
  for (float kappa : {1.0f, 2.0f}) {
    std::vector<vec3> points(3000);
    std::vector<float> h(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) {
      points[i] = vec3(u(rng), u(rng), 0.2f * u(rng));
      h[i] = 0.002f * std::exp2(exponent(rng));  // 0.002 to 1.02
    }
    const SupportGrid grid(points, h, kappa);
    EXPECT_EQ(grid.levels(), SupportGridView::kMaxLevels);
    const SupportGridView view = grid.view();
    for (int q = 0; q < 300; ++q) {
      const vec3 c(1.3f * u(rng), 1.3f * u(rng), u(rng));
      std::vector<int> found;
      view.for_each_covering(c, [&](vec3 p, float d2, int s) {
        const int i = grid.original_index()[std::size_t(s)];
        EXPECT_EQ(p, points[std::size_t(i)]);
        EXPECT_FLOAT_EQ(view.inv_h2[s], 1.0f / (h[std::size_t(i)] * h[std::size_t(i)]));
        EXPECT_FLOAT_EQ(d2, length2(p - c));
        found.push_back(i);
      });
      std::vector<int> brute;
      for (int i = 0; i < int(points.size()); ++i)
        if (length2(points[std::size_t(i)] - c) / (h[std::size_t(i)] * h[std::size_t(i)]) <= kappa * kappa)
          brute.push_back(i);
      std::sort(found.begin(), found.end());
      ASSERT_EQ(found, brute) << "query " << q;
    }
  }
}

TEST(SupportGrid, OneWidthIsOneLevelAndAnEmptyCloudOneEmptyLevel) {
  const std::vector<vec3> points = stepped_plane(0.1f, 1);
  const SupportGrid one(points, std::vector<float>(points.size(), 0.2f), 2.0f);
  EXPECT_EQ(one.levels(), 1);
  EXPECT_EQ(one.view().level[0].radius, 0.4f);
  const SupportGrid empty(std::vector<vec3>{}, std::vector<float>{}, 2.0f);
  EXPECT_EQ(empty.levels(), 1);
  int visited = 0;
  empty.view().for_each_covering(vec3(0.0f), [&](vec3, float, int) { ++visited; });
  EXPECT_EQ(visited, 0);
}

TEST(SupportGrid, RefusesWidthsThatAreNotPositiveOrMiscounted) {
  const std::vector<vec3> points{vec3(0.0f), vec3(1.0f)};
  EXPECT_THROW(SupportGrid(points, std::vector<float>{1.0f, 0.0f}, 2.0f), Error);
  EXPECT_THROW(SupportGrid(points, std::vector<float>{1.0f, NAN}, 2.0f), Error);
  EXPECT_THROW(SupportGrid(points, std::vector<float>{1.0f}, 2.0f), Error);
  EXPECT_THROW(SupportGrid(points, std::vector<float>{1.0f, 1.0f}, 0.0f), Error);
}

// A tile's grid on the whole cloud's layout (spatial/support_layout.hpp): the samples of a box
// and a halo as wide as the widest support, of widths over 16:1 (five levels), given in the
// cloud's order, walk every query within the box in the whole grid's order, sample for
// sample, and so every sum over them rounds alike. A grid of the same samples on a layout of
// their own walks them otherwise. Samples narrower than the layout's least width, or on a
// level it has not, are refused.
TEST(SupportGrid, ATilesGridOnTheCloudsLayoutWalksQueriesAsTheCloudsGrid) {
  std::mt19937 rng(12);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f), w(0.01f, 0.17f);
  std::vector<vec3> points(20000);
  std::vector<float> h(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    points[i] = vec3(u(rng), u(rng), 0.3f * u(rng));
    h[i] = w(rng);
  }
  const float kappa = 2;
  std::vector<int> all(points.size());
  std::iota(all.begin(), all.end(), 0);
  const SupportGrid whole(points, h, all, kappa);
  ASSERT_GE(whole.levels(), 4);
  SupportTally tally;
  tally.least = *std::min_element(h.begin(), h.end());
  for (std::size_t i = 0; i < points.size(); ++i) tally.add(points[i], h[i]);
  const SupportLayout layout = support_layout(tally, kappa);
  const Aabb box{vec3(-0.13f, 0.21f, -0.3f), vec3(0.37f, 0.64f, 0.3f)};
  const float halo = kappa * 0.17f;
  std::vector<int> tile;  // ascending: the cloud's order
  for (std::size_t i = 0; i < points.size(); ++i) {
    const vec3 p = glm::clamp(points[i], box.lo, box.hi);
    if (glm::length(points[i] - p) <= halo) tile.push_back(int(i));
  }
  const SupportGrid part(points, h, tile, layout);
  const SupportGrid own(points, h, tile, kappa);
  const auto walk = [&](const SupportGrid& grid, vec3 c) {
    std::vector<int> order;
    grid.view().for_each_covering(c, [&](vec3, float, int i) { order.push_back(grid.original_index()[std::size_t(i)]); });
    return order;
  };
  std::size_t walked = 0, otherwise = 0;
  for (int q = 0; q < 300; ++q) {
    const vec3 c = box.lo + (box.hi - box.lo) * (0.5f + 0.5f * vec3(u(rng), u(rng), u(rng)));
    const std::vector<int> expected = walk(whole, c);
    EXPECT_EQ(walk(part, c), expected) << q;
    otherwise += walk(own, c) != expected;
    walked += expected.size();
  }
  EXPECT_GT(walked, 300u * 20);
  EXPECT_GT(otherwise, 100u) << "a grid of its own walks as the whole cloud's: the test tells nothing";
  std::vector<float> narrower = h;
  narrower[std::size_t(tile[0])] = 0.5f * tally.least;
  EXPECT_THROW(SupportGrid(points, narrower, tile, layout), Error);
  std::vector<float> wider = h;  // on a level no sample of the layout's is
  wider[std::size_t(tile[0])] = 8 * 0.17f;
  EXPECT_THROW(SupportGrid(points, wider, tile, layout), Error);
}

}  // namespace
}  // namespace pss
