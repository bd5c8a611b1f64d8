// Clouds sampled in rows (issue 26, src/points/rows.hpp): a sphere sampled on rings far
// apart and densely along each, as blade.off is in slices. The widths of adaptive support
// span the gap between rings, and the sphere renders whole; with the width the neighbours
// along a ring give, it shows as a ladder of stripes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "pss/points/render_cloud.hpp"
#include "pss/points/support.hpp"
#include "support/render_truth.hpp"

namespace pss {
namespace {

constexpr float kPi = 3.14159265f;

// Rings of latitude `gap` apart on the unit sphere, sampled every `along` on each; the caps
// within 1.5 gaps of the poles are left out, as a slicer's first and last slices may be.
PointCloud rings(float gap, float along) {
  PointCloud cloud;
  const int count = int(std::lround(kPi / gap));
  for (int i = 1; i < count; ++i) {
    const float polar = kPi * float(i) / float(count);
    if (polar < 1.5f * gap || polar > kPi - 1.5f * gap) continue;
    const int around = int(std::lround(2 * kPi * std::sin(polar) / along));
    for (int k = 0; k < around; ++k) {
      const float a = 2 * kPi * (float(k) + 0.5f * float(i % 2)) / float(around);
      cloud.positions.push_back(vec3(std::sin(polar) * std::cos(a), std::sin(polar) * std::sin(a), std::cos(polar)));
    }
  }
  return cloud;
}

// The rings 0.13 apart, 0.005 along: the 15 nearest neighbours all lie on a sample's ring.
// Its width spans the gap (about 0.75 of it, kSupportWidening), where the plain width
// stays at the ring's own spacing.
TEST(Rows, ARingsWidthSpansTheGapToTheNext) {
  const PointCloud cloud = rings(0.13f, 0.005f);
  const float h = test::suggested_h(cloud);
  ASSERT_LT(h, 0.05f);
  ProjectionParams params = ProjectionParams::from_h(h);
  params.support = Support::adaptive;
  const SupportWidths widths = support_widths(cloud.positions, params);
  std::printf("h %.4f, widths %.4f / %.4f / %.4f\n", double(h), double(widths.least), double(widths.median),
              double(widths.largest));
  EXPECT_GT(widths.median, 0.6f * 0.13f);
  EXPECT_LT(widths.median, 0.9f * 0.13f);
}

// One ring beside a sphere sampled at random is no cloud of rows: its samples keep the
// plain width (the ring lies 0.5 from the sphere, which would widen them past h).
TEST(Rows, AFewRowsInACloudAreNotACloudOfRows) {
  test::SampleOptions o;
  o.count = 20000;
  PointCloud cloud = test::sample(test::Sphere{}, o);
  for (int k = 0; k < 2000; ++k) {
    const float a = 2 * kPi * float(k) / 2000;
    cloud.positions.push_back(vec3(1.5f * std::cos(a), 1.5f * std::sin(a), 0.0f));
  }
  const float h = test::suggested_h(cloud);
  ProjectionParams params = ProjectionParams::from_h(h);
  params.support = Support::adaptive;
  params.outliers = OutlierPolicy::keep;
  const SupportWidths widths = support_widths(cloud.positions, params);
  EXPECT_EQ(*std::max_element(widths.h.begin() + 20000, widths.h.end()), h);
}

// Rendered against the analytic sphere (away from the open caps): whole with adaptive
// support; a ladder with one width.
TEST(Rows, ASphereSampledInRingsRendersWhole) {
  const PointCloud cloud = rings(0.13f, 0.005f);
  const float h = test::suggested_h(cloud);
  const auto render = [&](Support support) {
    RayPssParams params = RayPssParams::from_h(h);
    params.projection.support = support;
    return test::against_sphere(test::render_at_160(cloud, params, Backend::cpu, cloud.bounds(), 30, 10, vec3(0, 0, 1)),
                                test::Sphere{}, 0.05f);
  };
  const test::RenderTruth adaptive = render(Support::adaptive), global = render(Support::global);
  std::printf("holes: adaptive %lld, one width %lld of %lld\n", (long long)adaptive.holes, (long long)global.holes,
              (long long)adaptive.data_pixels);
  ASSERT_GT(adaptive.data_pixels, 4000);
  EXPECT_LE(adaptive.hole_fraction(), 0.003);
  EXPECT_LE(adaptive.extra_fraction(), 0.002);
  EXPECT_LT(adaptive.mean_distance, 0.005);
  EXPECT_GT(global.hole_fraction(), 0.2);
}

}  // namespace
}  // namespace pss
