// Merged samples where noise widens the supports (points/merged_samples.hpp, issue 26): a
// sample's mass weighs it as that many coincident samples in every surface's fits; the cubes
// merge to their means; a noisy cloud is merged and its surface stays as close to the truth
// as with every sample, while clean clouds keep every sample.
#include <gtest/gtest.h>

#include <cmath>
#include <numeric>
#include <random>

#include "pss/points/merged_samples.hpp"
#include "pss/points/outliers.hpp"
#include "pss/points/project_cloud.hpp"
#include "pss/points/sample_normals.hpp"
#include "pss/points/spacing.hpp"
#include "pss/points/support.hpp"
#include "pss/points/surface_projection.hpp"
#include "support/shapes.hpp"

namespace pss {
namespace {

// A noisy unit sphere whose samples 0, 7, 14, ... weigh 3, against the same cloud with those
// samples there three times: every surface projects the same.
TEST(MergedSamples, ASampleOfMassThreeActsAsThreeCoincidentSamples) {
  test::SampleOptions o;
  o.count = 3000;
  o.noise = 0.01f;
  const PointCloud cloud = test::sample(test::Sphere{}, o);
  const float h = test::suggested_h(cloud);
  std::vector<vec3> copies = cloud.positions;
  std::vector<int> into(cloud.size()), samples(cloud.size());
  std::iota(into.begin(), into.end(), 0);
  std::iota(samples.begin(), samples.end(), 0);
  for (std::size_t i = 0; i < cloud.size(); i += 7) {
    for (int copy = 0; copy < 2; ++copy) {
      copies.push_back(cloud.positions[i]);
      into.push_back(int(i));
    }
  }
  // The grid holds the cloud's points; each copy joins its original's sample.
  SupportGrid weighed(copies, std::vector<float>(copies.size(), h), samples, 2.0f);
  weighed.set_members(into);
  const SupportGrid repeated(copies, std::vector<float>(copies.size(), h), 2.0f);
  ASSERT_EQ(weighed.masses().size(), cloud.size());
  EXPECT_EQ(*std::max_element(weighed.masses().begin(), weighed.masses().end()), 3.0f);
  auto normals_of = [](const SupportGrid& g) {
    std::vector<vec3> n;
    for (const vec3& p : g.sorted_points()) n.push_back(glm::normalize(p));
    return n;
  };
  weighed.set_normals(normals_of(weighed));
  SupportGrid repeated_with_normals(copies, std::vector<float>(copies.size(), h), 2.0f);
  repeated_with_normals.set_normals(normals_of(repeated_with_normals));
  std::mt19937 rng(4);
  std::normal_distribution<float> gauss(0.0f, 1.0f);
  for (const SurfaceOperator surface : {SurfaceOperator::mls, SurfaceOperator::apss, SurfaceOperator::rimls}) {
    SCOPED_TRACE(int(surface));
    ProjectionParams params = ProjectionParams::from_h(h);
    params.surface = surface;
    float largest = 0, moved = 0;
    for (int q = 0; q < 200; ++q) {
      const vec3 d = glm::normalize(vec3(gauss(rng), gauss(rng), gauss(rng)));
      const vec3 r = d * (1 + 0.3f * h * gauss(rng));
      const Projection a = project_onto_surface(weighed.view(), r, params, d);
      const Projection b = project_onto_surface(repeated_with_normals.view(), r, params, d);
      ASSERT_EQ(a.status, b.status);
      largest = std::max(largest, glm::length(a.point - b.point));
      moved = std::max(moved, glm::length(a.point - r));
    }
    EXPECT_LT(largest, 1e-3f * h);  // float rounding of sums in another order
    EXPECT_GT(moved, 0.1f * h);  // the queries were off the surface: the test can tell
    // Without the masses the weighed samples count once: the surface moves measurably.
    SupportGrid once(cloud.positions, std::vector<float>(cloud.size(), h), 2.0f);
    once.set_normals(normals_of(once));
    float apart = 0;
    for (int q = 0; q < 200; ++q) {
      const vec3 d = glm::normalize(vec3(gauss(rng), gauss(rng), gauss(rng)));
      apart = std::max(apart, glm::length(project_onto_surface(once.view(), d, params, d).point -
                                          project_onto_surface(repeated_with_normals.view(), d, params, d).point));
    }
    EXPECT_GT(apart, 10 * largest);
  }
}

TEST(MergedSamples, TheMarkedPointsOfACubeMergeToTheirMeanAndCount) {
  const float h = 1.0f;  // cubes of side 2^⌊log2(kMergeCell)⌋ = 1
  ASSERT_EQ(std::ilogb(kMergeCell * h), 0);
  const std::vector<vec3> points = {{0.1f, 0.1f, 0.1f}, {5.5f, 0.5f, 0.5f}, {0.7f, 0.3f, 0.9f}, {0.4f, 0.8f, 0.2f},
                                    {1.2f, 0.5f, 0.5f}, {0.5f, 0.5f, 0.5f}};
  const std::vector<float> widths = {h, h, h, h, h, 0.25f};  // the last: cubes of another side
  const std::vector<char> merge = {1, 1, 1, 0, 1, 1};
  const MergedSamples m = merge_samples(points, widths, merge);
  // 0 and 2 share the cube [0,1)³; 3 is not marked; 1, 4 and 5 are alone in theirs.
  EXPECT_EQ(m.samples, (std::vector<int>{0, 1, 3, 4, 5}));
  EXPECT_EQ(m.into, (std::vector<int>{0, 1, 0, 3, 4, 5}));
  EXPECT_NEAR(m.positions[0].x, 0.4f, 1e-6f);
  EXPECT_NEAR(m.positions[0].y, 0.2f, 1e-6f);
  EXPECT_NEAR(m.positions[0].z, 0.5f, 1e-6f);
  EXPECT_EQ(m.positions[3], points[3]);
  EXPECT_EQ(m.positions[4], points[4]);
}

// A merged sample's file normal is the mean of its points' normals, each turned first to the
// side of the sample's own (a file whose normals face both ways: the seams' turn comes after).
TEST(MergedSamples, AMergedSamplesFileNormalIsItsPointsMeanTurnedToItsSide) {
  const std::vector<vec3> points = {{0, 0, 0}, {0.1f, 0, 0}, {0, 0.1f, 0}, {0.1f, 0.1f, 0}, {3, 0, 0}};
  const std::vector<vec3> normals = {{0, 0, 1}, glm::normalize(vec3(0.4f, 0, 1)), {0, 0, -1},
                                     glm::normalize(vec3(0, -0.6f, 1)), {0, 0, 1}};
  const std::vector<int> samples = {0, 4}, into = {0, 0, 0, 0, 4};
  SupportGrid grid(points, std::vector<float>(points.size(), 0.5f), samples, 2.0f);
  grid.set_members(into);
  Stats stats;
  const FileNormals file = file_normals(grid, normals, ProjectionParams::from_h(0.5f), stats);
  ASSERT_EQ(file.sorted.size(), 2u);
  const vec3 expected = glm::normalize(normals[0] + normals[1] - normals[2] + normals[3]);
  for (std::size_t k = 0; k < 2; ++k) {
    const int i = grid.original_index()[k];
    const vec3 want = i == 0 ? expected : normals[4];
    EXPECT_NEAR(glm::dot(file.sorted[k], want), 1.0f, 1e-6f) << i;
  }
}

// 60,000 points of the torus with noise of 4 spacings (0.06).
test::SampleOptions noisy_torus_options() {
  test::SampleOptions o;
  o.count = 60000;
  o.noise = 0.06f;
  return o;
}

// A torus with noise of 4 spacings: h = 3σ puts about 3,000 samples in each support. Merged,
// the grid holds a fraction of them, and the projections are as close to the true torus as
// those with every sample at the same widths (global support merges none).
TEST(MergedSamples, ANoisyTorusIsMergedAndProjectsAsCloseToTheTruth) {
  const test::SampleOptions o = noisy_torus_options();
  const test::Torus torus;
  PointCloud cloud = test::sample(torus, o);
  const float h = test::suggested_h(cloud);
  ASSERT_GT(h, 2.5f * o.noise);  // the noise set it
  // Strays 5σ off the torus, each alone: set aside, as they are without merging (the
  // threshold weighs the merged samples' masses; counted once each, the few points of the
  // cubes at the noise's edge set it near 2.4 h).
  const std::size_t surface = cloud.size();
  for (int i = 0; i < 30; ++i) {
    const float u = 0.21f * float(i), v = 0.37f * float(i);
    const vec3 on(std::cos(u) * (torus.major + torus.minor * std::cos(v)),
                  std::sin(u) * (torus.major + torus.minor * std::cos(v)), torus.minor * std::sin(v));
    cloud.positions.push_back(on + 5 * o.noise * torus.normal(on));
  }
  ProjectionParams adaptive = ProjectionParams::from_h(h);
  adaptive.support = Support::adaptive;
  const SupportWidths widths = support_widths(cloud.positions, adaptive);
  EXPECT_GT(widths.merged_count, std::int64_t(cloud.size() * 3 / 4));
  Stats stats;
  OutlierReport report;
  const SupportGrid grid = grid_of_samples(cloud.positions, widths.h, widths.merged, 2.0f, OutlierPolicy::set_aside,
                                           Backend::cpu, stats, report);
  EXPECT_LT(grid.sorted_points().size(), cloud.size() / 3);
  EXPECT_LT(report.set_aside, std::int64_t(cloud.size() / 100));
  std::vector<char> sample(cloud.size(), 0);
  for (const int i : grid.original_index()) sample[std::size_t(i)] = 1;
  int strays_kept = 0;
  for (std::size_t i = surface; i < cloud.size(); ++i) strays_kept += sample[i];
  EXPECT_EQ(strays_kept, 0);

  auto mean_error = [&](const ProjectionParams& params, std::int64_t& merged, std::size_t& n) {
    PointCloud copy = cloud;
    Stats s;
    const CloudProjection p = project_cloud(std::move(copy), params, Backend::cpu, s);
    merged = p.widths.merged_count;
    double sum = 0;
    n = 0;
    std::size_t inward = 0;  // merged, the tree grows over the samples' points; the rest follow
    for (std::size_t i = 0; i < p.cloud.size(); ++i)
      if (p.status[i] == ProjectionStatus::converged) {
        sum += std::abs(torus.distance(p.cloud.positions[i]));
        inward += glm::dot(p.cloud.normals[i], torus.normal(p.cloud.positions[i])) < 0;
        ++n;
      }
    EXPECT_GT(n, surface * 9 / 10);
    EXPECT_EQ(inward, 0u);
    return sum / double(n);
  };
  std::int64_t merged = 0, none = 0;
  std::size_t converged_merged = 0, converged_all = 0;
  const double with_merged = mean_error(adaptive, merged, converged_merged);
  ProjectionParams global = adaptive;
  global.support = Support::global;
  const double with_all = mean_error(global, none, converged_all);
  // Points 3σ out with supports as wide as the tube still move at the iteration cap, a few
  // percent of them (4.6 % with every sample); merging leaves about as many.
  EXPECT_GT(converged_merged, converged_all * 97 / 100);
  EXPECT_GT(merged, 0);
  EXPECT_EQ(none, 0);
  EXPECT_LT(with_merged, 1.1 * with_all);
  EXPECT_LT(with_all, 0.35 * o.noise);  // both smooth the noise away, but for the curvature bias
}

// Merged, every point is projected (in the grid's cells' order, not the file's), each with its
// own file normal as the hint that turns its projection's normal: all face as the file says.
TEST(MergedSamples, EveryPointOfAMergedCloudFacesAsItsFileNormal) {
  const test::Torus torus;
  PointCloud cloud = test::sample(torus, noisy_torus_options());
  cloud.normals.resize(cloud.size());
  for (std::size_t i = 0; i < cloud.size(); ++i) cloud.normals[i] = torus.normal(cloud.positions[i]);
  ProjectionParams params = ProjectionParams::from_h(test::suggested_h(cloud));
  params.support = Support::adaptive;
  Stats stats;
  const CloudProjection p = project_cloud(cloud, params, Backend::cpu, stats);
  EXPECT_GT(p.widths.merged_count, std::int64_t(cloud.size() / 2));
  EXPECT_EQ(p.normals_turned, 0u);
  std::size_t against = 0, converged = 0;
  for (std::size_t i = 0; i < p.cloud.size(); ++i)
    if (p.status[i] == ProjectionStatus::converged) {
      ++converged;
      against += glm::dot(p.cloud.normals[i], cloud.normals[i]) < 0;
    }
  EXPECT_GT(converged, cloud.size() * 9 / 10);
  EXPECT_EQ(against, 0u);
}

// Clean clouds, evenly or unevenly sampled, keep every sample; so does a clean plane scanned
// in dense rows far apart, whose supports (as wide as the rows' gaps) hold thousands of samples
// but no noise.
TEST(MergedSamples, CleanCloudsAreNotMerged) {
  std::vector<PointCloud> clouds;
  for (const bool nonuniform : {false, true}) {
    test::SampleOptions o;
    o.count = 20000;
    o.nonuniform = nonuniform;
    clouds.push_back(test::sample(test::Torus{}, o));
  }
  PointCloud rows;
  for (int j = 0; j < 20; ++j)
    for (int i = 0; i < 2000; ++i) rows.positions.push_back(vec3(0.0005f * float(i), 0.05f * float(j), 0.0f));
  clouds.push_back(rows);
  for (const PointCloud& cloud : clouds) {
    ProjectionParams params = ProjectionParams::from_h(test::suggested_h(cloud));
    params.support = Support::adaptive;
    const SupportWidths widths = support_widths(cloud.positions, params);
    EXPECT_EQ(widths.merged_count, 0);
    EXPECT_TRUE(widths.merged.empty());
  }
  // The rows' supports do hold thousands: only the noise's absence keeps them.
  EXPECT_TRUE(merges_samples(0.05f, 0.004f, 0.001f, 2.0f));
  EXPECT_FALSE(merges_samples(0.05f, 0.004f, 0.0f, 2.0f));
  // In thin noise a support of ρ = 2h holds 15·(2h/s)² samples: about 600 at h = 3.16 s,
  // merged (over 400: a noisy torus's render 18× faster, as close to the truth), 240 at 2 s not.
  EXPECT_TRUE(merges_samples(3.16f, 1.0f, 0.01f, 2.0f));
  EXPECT_FALSE(merges_samples(2.0f, 1.0f, 0.01f, 2.0f));
  // The cloud's noise counts where it set h (h = kNoiseWidths·σ̂ over twice the spacing),
  // not where h is the spacing's.
  EXPECT_FLOAT_EQ(noise_of_h(0.3f, 0.1f), float(0.3 / kNoiseWidths));
  EXPECT_EQ(noise_of_h(0.15f, 0.1f), 0.0f);
}

// The outliers' threshold (outliers.hpp) weighs each distance by its sample's mass: a few
// light samples far off do not set it.
TEST(MergedSamples, TheOutliersThresholdWeighsTheMasses) {
  const std::vector<float> distance = {0.2f, 1.0f, 1.0f, 1.0f};
  EXPECT_NEAR(outlier_threshold(distance), kOutlierSigmas * 1.4826f * 1.0f, 1e-5f);
  const std::vector<float> mass = {10, 1, 1, 1};
  EXPECT_NEAR(outlier_threshold(distance, mass), kOutlierSigmas * 1.4826f * 0.2f, 1e-5f);
}

}  // namespace
}  // namespace pss
