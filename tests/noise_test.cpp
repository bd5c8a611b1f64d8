// The noise a cloud's samples scatter with about their surface (points/noise.hpp, issue 26),
// against the σ of the Gaussian noise the test put on analytic shapes, and the default h it
// raises: at least kNoiseWidths·σ, where a width set by the spacing alone meshes a noisy
// surface into bubbles.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <utility>
#include <vector>

#include "pss/mesh/mesh_cloud.hpp"
#include "pss/mesh/triangle_mesh.hpp"
#include "pss/points/noise.hpp"
#include "pss/points/spacing.hpp"
#include "pss/spatial/uniform_grid.hpp"
#include "support/shapes.hpp"

namespace pss {
namespace {

PointCloud noisy(const auto& shape, std::size_t count, float noise) {
  test::SampleOptions o;
  o.count = count;
  o.noise = noise;
  return test::sample(shape, o);
}

// On a sphere and a torus (curved, so that a plane's residual would take the curvature for
// noise), with σ from a twentieth of the spacing's h to two thirds of it: σ to within 10 %,
// and h the larger of the spacing's and kNoiseWidths·σ.
TEST(Noise, IsTheSigmaOfTheNoiseAboutACurvedSurface) {
  for (const float sigma : {0.004f, 0.02f, 0.04f}) {
    SCOPED_TRACE(sigma);
    for (const PointCloud& cloud : {noisy(test::Sphere{}, 20000, sigma), noisy(test::Torus{}, 20000, sigma)}) {
      const SpacingEstimate e = estimate_spacing(cloud.positions);
      EXPECT_NEAR(e.noise, sigma, 0.1 * sigma) << "the 15th neighbour at " << e.median_kth;
      EXPECT_DOUBLE_EQ(e.suggested_h, std::max(e.median_kth, kNoiseWidths * e.noise));
    }
  }
  // Where the noise is over a third of the spacing's h, it sets h.
  const SpacingEstimate e = estimate_spacing(noisy(test::Torus{}, 20000, 0.04f).positions);
  EXPECT_GT(e.suggested_h, 1.3 * e.median_kth);
}

TEST(Noise, ACleanCurvedSurfaceHasNone) {
  for (const PointCloud& cloud : {noisy(test::Sphere{}, 20000, 0), noisy(test::Torus{}, 20000, 0)}) {
    const SpacingEstimate e = estimate_spacing(cloud.positions);
    EXPECT_LT(e.noise, 1e-3 * e.median_kth);
    EXPECT_EQ(e.suggested_h, e.median_kth);
  }
}

// Two clean parallel sheets, closer than the spacing's h and farther: the noise never raises
// h (a thin part is not a noisy one, and must not be blurred into one sheet), and with the
// sheets a spacing's h apart or more each query sees one sheet: no noise. Nor in a thin closed
// part, its faces 0.06 apart, nor in points along a line (a cloud of rows).
TEST(Noise, ThinPartsAndRowsAreNotNoise) {
  const PointCloud sheet = test::sample_plane(1.0f, test::SampleOptions{});
  test::SampleOptions other;
  other.seed = 5;
  const PointCloud second = test::sample_plane(1.0f, other);
  const double kth = estimate_spacing(sheet.positions).median_kth;
  for (const double gap : {0.25 * kth, 0.5 * kth, 0.75 * kth, kth, 1.5 * kth}) {
    SCOPED_TRACE(gap / kth);
    std::vector<vec3> two = sheet.positions;
    for (const vec3& p : second.positions) two.push_back(p + vec3(0.0f, 0.0f, float(gap)));
    const SpacingEstimate e = estimate_spacing(two);
    EXPECT_EQ(e.suggested_h, e.median_kth) << "noise " << e.noise;
    if (gap >= kth) EXPECT_LT(e.noise, 1e-3 * gap);
  }
  test::SampleOptions o;
  o.count = 30000;
  const SpacingEstimate pill = estimate_spacing(test::sample(test::Pill{}, o).positions);
  EXPECT_EQ(pill.suggested_h, pill.median_kth) << "noise " << pill.noise;
  std::vector<vec3> line;
  for (int i = 0; i < 1000; ++i) line.push_back(vec3(0.01f * float(i), 0.5f, 0.25f));
  EXPECT_EQ(estimate_spacing(line).noise, 0);
}

// A noisy thin part, its faces a spacing's h or 1.5 of it apart, each with noise a fifth or
// less of that h: a ball wide enough to see across one face's noise takes in the other face
// too, and that must not count as noise (h tripled merged such a box's faces into one
// sheet). h stays the spacing's.
TEST(Noise, TheFacesOfANoisyThinPartAreNotNoise) {
  const double kth = estimate_spacing(test::sample_plane(1.0f, test::SampleOptions{}).positions).median_kth;
  for (const auto [gap, sigma] : {std::pair{1.0, 0.2}, {1.5, 0.3}, {0.5, 0.1}, {2.0, 0.3}}) {
    SCOPED_TRACE(testing::Message() << "gap " << gap << ", noise " << sigma);
    test::SampleOptions o;
    o.noise = float(sigma * kth);
    std::vector<vec3> two = test::sample_plane(1.0f, o).positions;
    o.seed = 5;
    for (const vec3& p : test::sample_plane(1.0f, o).positions) two.push_back(p + vec3(0.0f, 0.0f, float(gap * kth)));
    const SpacingEstimate e = estimate_spacing(two);
    EXPECT_EQ(e.suggested_h, e.median_kth) << "noise " << e.noise / kth << " kth";
  }
}

// Points that fill a volume (trees in a LiDAR tile) scatter about any fitted surface by a
// third of the reach, however wide: no noise about a surface, h unchanged; and the reach
// stops at kNoiseReachMost k-th distances, so the estimate's work stays bounded. On ground
// beside such a volume, the ground's noise.
TEST(Noise, PointsThatFillAVolumeAreNotNoise) {
  std::mt19937 rng(2);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::vector<vec3> volume(20000);
  for (vec3& p : volume) p = vec3(unit(rng), unit(rng), unit(rng));
  const SpacingEstimate e = estimate_spacing(volume);
  EXPECT_EQ(e.suggested_h, e.median_kth) << "noise " << e.noise;
  const UniformGrid grid(volume, 1e-7f, 20000);
  int surfaces = 0;
  for (std::size_t i = 0; i < 200; ++i) {
    const QueryNoise q = noise_near(grid.view(), volume[i], e.median_kth);
    EXPECT_LE(q.reach, kNoiseReachMost * e.median_kth * (1 + 1e-6));
    surfaces += std::isfinite(q.sigma);
  }
  EXPECT_LT(surfaces, 40) << "of 200 queries found a noisy surface in a volume";
  // 8,000 ground points with noise 0.002, and 12,000 of the volume above it.
  test::SampleOptions o;
  o.count = 8000;
  o.noise = 0.002f;
  std::vector<vec3> forest = test::sample_plane(1.0f, o).positions;
  for (std::size_t i = 0; i < 12000; ++i) forest.push_back(volume[i] * 0.5f + vec3(0.0f, 0.0f, 0.2f));
  EXPECT_NEAR(estimate_spacing(forest).noise, 0.002, 0.0004);
}

// Where the spacing's h ~ the noise, the PSS has bubbles around single samples: a unit
// sphere with noise 0.55 times the spacing's h meshes into several parts with holes at that h,
// and into one watertight part with the default (pss mesh without --h).
TEST(Noise, ANoisySurfaceMeshesWholeWithTheDefaultH) {
  const PointCloud cloud = noisy(test::Sphere{}, 8000, 0.06f);
  const SpacingEstimate e = estimate_spacing(cloud.positions);
  ASSERT_GT(e.noise, 0.5 * e.median_kth);
  for (const double h : {e.median_kth, e.suggested_h}) {
    MeshParams params;
    params.projection = ProjectionParams::from_h(float(h));
    params.projection.support = Support::adaptive;
    Stats stats;
    const MeshTopology t = topology(mesh_cloud(cloud, params, Backend::cpu, stats).mesh);
    if (h == e.suggested_h) {
      EXPECT_EQ(t.components, 1);
      EXPECT_TRUE(t.watertight());
    } else {
      EXPECT_FALSE(t.components == 1 && t.watertight()) << "the noise does not shred this sphere: no test";
    }
  }
}

}  // namespace
}  // namespace pss
