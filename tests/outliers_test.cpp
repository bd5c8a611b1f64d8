// Samples set aside as off the surface (points/outliers.hpp, issue 26): strays near and far
// from an analytic sphere are set aside, its samples kept, clean or noisy, and a box keeps its
// creases' samples; rendered, the strays leave no flakes, which they do when kept.
#include <gtest/gtest.h>

#include <random>

#include "pss/points/outliers.hpp"
#include "pss/points/render_cloud.hpp"
#include "pss/points/support.hpp"
#include "support/shapes.hpp"

namespace pss {
namespace {

struct Strewn {
  PointCloud cloud;
  std::size_t surface = 0;  // the first `surface` points are the sphere's
  float h = 0;
};

// A unit sphere (noise σ along the normal) and strays: 60 at 1h to 3h off it, 60 strewn
// through its box.
Strewn sphere_with_strays(float noise_in_h) {
  Strewn s;
  test::SampleOptions o;
  o.count = 12000;
  s.h = test::suggested_h(test::sample(test::Sphere{}, o));
  o.noise = noise_in_h * s.h;
  s.cloud = test::sample(test::Sphere{}, o);
  s.surface = s.cloud.size();
  std::mt19937 rng(9);
  std::normal_distribution<float> gauss(0.0f, 1.0f);
  std::uniform_real_distribution<float> uni(0.0f, 1.0f);
  for (int i = 0; i < 60; ++i) {
    const vec3 d = glm::normalize(vec3(gauss(rng), gauss(rng), gauss(rng)));
    const float off = (1 + 2 * uni(rng)) * s.h * (i % 2 ? 1.0f : -1.0f);
    s.cloud.positions.push_back(d * (1 + off));
  }
  for (int i = 0; i < 60; ++i) s.cloud.positions.push_back(vec3(uni(rng), uni(rng), uni(rng)) * 3.0f - 1.5f);
  return s;
}

// keep[i] in the input's order: whether the grid of the samples holds point i.
std::vector<char> kept(const PointCloud& cloud, float h, OutlierReport& report) {
  ProjectionParams params = ProjectionParams::from_h(h);
  params.support = Support::global;
  Stats stats;
  const SupportGrid grid = grid_of_samples(cloud.positions, support_widths(cloud.positions, params).h, {}, 2,
                                           OutlierPolicy::set_aside, Backend::cpu, stats, report);
  std::vector<char> keep(cloud.size(), 0);
  for (int i : grid.original_index()) keep[std::size_t(i)] = 1;
  EXPECT_EQ(report.set_aside, std::int64_t(cloud.size() - grid.original_index().size()));
  return keep;
}

TEST(Outliers, StraysAreSetAsideAndTheSphereKept) {
  for (float noise : {0.0f, 0.1f}) {
    SCOPED_TRACE(noise);
    const Strewn s = sphere_with_strays(noise);
    OutlierReport report;
    const std::vector<char> keep = kept(s.cloud, s.h, report);
    std::size_t surface_set_aside = 0, strays_off = 0, strays_off_kept = 0;
    for (std::size_t i = 0; i < s.surface; ++i) surface_set_aside += !keep[i];
    // A stray within the floor's distance of the sphere is as close as noise may lie.
    for (std::size_t i = s.surface; i < keep.size(); ++i)
      if (std::abs(test::Sphere{}.distance(s.cloud.positions[i])) > (kOutlierFloor + 0.1f) * s.h) {
        ++strays_off;
        strays_off_kept += keep[i];
      }
    EXPECT_EQ(surface_set_aside, 0u);
    EXPECT_GT(strays_off, 100u);
    EXPECT_EQ(strays_off_kept, 0u);
    EXPECT_FLOAT_EQ(report.threshold, kOutlierFloor);  // the noise is below the floor's
  }
}

// Noise of 0.3h: the threshold follows it (4 robust σ), and the sphere keeps its samples but
// for the noise's own tail.
TEST(Outliers, TheThresholdFollowsTheNoise) {
  const Strewn s = sphere_with_strays(0.3f);
  OutlierReport report;
  const std::vector<char> keep = kept(s.cloud, s.h, report);
  EXPECT_GT(report.threshold, kOutlierFloor);
  std::size_t surface_set_aside = 0;
  for (std::size_t i = 0; i < s.surface; ++i) surface_set_aside += !keep[i];
  EXPECT_LT(surface_set_aside, s.surface / 1000);
}

// A clean CAD-like part: the box [-1, 1]³ sampled on a grid on each face. Its creases'
// samples lie off their neighbours' plane (fitted across the edge) by less than the floor.
TEST(Outliers, ABoxKeepsItsCreases) {
  PointCloud box;
  const float spacing = 0.04f;
  const int n = int(std::round(2 / spacing));
  for (int axis = 0; axis < 3; ++axis)
    for (float side : {-1.0f, 1.0f})
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
          vec3 p;
          p[axis] = side;
          p[(axis + 1) % 3] = -1 + (i + 0.5f) * spacing;
          p[(axis + 2) % 3] = -1 + (j + 0.5f) * spacing;
          box.positions.push_back(p);
        }
  OutlierReport report;
  kept(box, test::suggested_h(box), report);
  EXPECT_EQ(report.set_aside, 0);
}

// Rendered: hits more than 5 % of the radius off the sphere are the strays' flakes.
TEST(Outliers, StraysSetAsideLeaveNoFlakes) {
  const Strewn s = sphere_with_strays(0.1f);
  const auto off_surface = [&](OutlierPolicy policy, std::int64_t& set_aside) {
    RayPssParams params = RayPssParams::from_h(s.h);
    params.projection.outliers = policy;
    Stats stats;
    const PreparedCloud prepared(s.cloud, params, Backend::cpu, stats);
    set_aside = prepared.outliers().set_aside;
    CameraSettings view;
    view.width = view.height = 128;
    view.azimuth_deg = 30;
    view.elevation_deg = 20;
    const Camera camera = Camera::framing(s.cloud.bounds(), view);
    const RenderedFrame frame = render_cloud(prepared, camera, TraceSettings::for_camera(camera, false, false),
                                             Backend::cpu, stats);
    std::int64_t off = 0;
    for (const Hit& hit : frame.hits) off += hit.found() && std::abs(test::Sphere{}.distance(hit.point)) > 0.05f;
    return off;
  };
  std::int64_t kept_count = 0, set_aside_count = 0;
  const std::int64_t with_strays = off_surface(OutlierPolicy::keep, kept_count);
  const std::int64_t without = off_surface(OutlierPolicy::set_aside, set_aside_count);
  EXPECT_EQ(kept_count, 0);
  std::int64_t strays_off = 0;  // farther off the sphere than noise may lie
  for (std::size_t i = s.surface; i < s.cloud.size(); ++i)
    strays_off += std::abs(test::Sphere{}.distance(s.cloud.positions[i])) > (kOutlierFloor + 0.1f) * s.h;
  EXPECT_GE(set_aside_count, strays_off);
  EXPECT_LE(set_aside_count, 120);
  EXPECT_EQ(without, 0);
  EXPECT_GT(with_strays, 20) << "the strays make no flakes: the test shows nothing";
}

// A sphere whose noise (σ = 0.04) sets h, so that its supports hold some 400 samples, with
// 1 % of its points strewn through the shell about it: each stray has a few others in reach
// and a plane through them passes near it, so the plane's distance and the rule of 3 kept
// 77 of the 300 (floating flakes, a noisy torus's in docs/paper-notes.md); their
// neighbours' masses, a small share of the surface's, set them aside.
TEST(Outliers, StraysAmongEachOtherWhereTheNoiseWidensTheSupportsAreSetAside) {
  test::SampleOptions o;
  o.count = 30000;
  o.noise = 0.04f;
  PointCloud cloud = test::sample(test::Sphere{}, o);
  const std::size_t surface = cloud.size();
  std::mt19937 rng(4);
  std::normal_distribution<float> gauss(0.0f, 1.0f);
  std::uniform_real_distribution<float> uni(0.0f, 1.0f);
  for (int i = 0; i < 300; ++i) {
    const vec3 d = glm::normalize(vec3(gauss(rng), gauss(rng), gauss(rng)));
    cloud.positions.push_back(d * (1.35f + 0.25f * uni(rng)));  // 9σ to 15σ out
  }
  ProjectionParams params = ProjectionParams::from_h(test::suggested_h(cloud));
  params.support = Support::adaptive;
  ASSERT_GT(params.h, 2.5f * o.noise);  // the noise set it
  const SupportWidths widths = support_widths(cloud.positions, params);
  Stats stats;
  OutlierReport report;
  const SupportGrid grid = grid_of_samples(cloud.positions, widths.h, widths.merged, 2, OutlierPolicy::set_aside,
                                           Backend::cpu, stats, report);
  std::vector<char> sample(cloud.size(), 0);
  for (const int i : grid.original_index()) sample[std::size_t(i)] = 1;
  std::size_t strays_kept = 0;
  for (std::size_t i = surface; i < cloud.size(); ++i) strays_kept += sample[i];
  EXPECT_LE(strays_kept, 3u);
  EXPECT_GT(report.least_held, 3.0f);
  EXPECT_LT(report.set_aside, std::int64_t(300 + surface / 200));
}

}  // namespace
}  // namespace pss
