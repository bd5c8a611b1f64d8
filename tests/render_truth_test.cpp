// Each surface kind renders a noisy sphere with 1 % strays (issue 26: scanner noise of half
// the spacing, outliers) as the sphere: no holes where it is, no flakes off it, hits on it
// within the noise, normals within a few degrees; kept instead of set aside, the strays show.
#include <gtest/gtest.h>

#include <cstdio>

#include "pss/points/projection.hpp"
#include "pss/points/render_cloud.hpp"
#include "support/render_truth.hpp"

namespace pss {
namespace {

TEST(RenderTruth, NoisySphereWithStraysIsTheSphereForEverySurface) {
  const PointCloud cloud = test::noisy_sphere_with_strays(12000, 0.5f, 0.01f);
  for (const SurfaceOperator surface : {SurfaceOperator::mls, SurfaceOperator::apss, SurfaceOperator::rimls}) {
    const test::RenderTruth t = test::render_sphere(cloud, surface, OutlierPolicy::set_aside, Backend::cpu);
    test::expect_like_the_sphere(t, surface_name(surface));
  }
}

// The same strays kept as samples: flakes off the sphere, so the test above can fail.
TEST(RenderTruth, StraysKeptShowAsExtraSurface) {
  const PointCloud cloud = test::noisy_sphere_with_strays(12000, 0.5f, 0.01f);
  const test::RenderTruth t = test::render_sphere(cloud, SurfaceOperator::mls, OutlierPolicy::keep, Backend::cpu);
  std::printf("kept: extra %lld of %lld\n", (long long)t.extra, (long long)t.data_pixels);
  EXPECT_GT(t.extra_fraction(), 0.002);
}

// A CAD part with creases and exact normals in the file (a cube with a bore): every surface
// kind renders it without holes or extra surface (issue 26's goals for CAD parts: <= 0.5 %
// and <= 1 %), flat faces with their normals; by the creases RIMLS keeps the faces' normals
// where MLS's planes, fitted across the edge, turn.
TEST(RenderTruth, ABoredBoxKeepsItsFacesAndRimlsItsCreases) {
  const test::BoredBox box;
  const PointCloud cloud = test::sample(box, 0.03f);
  const float h = test::suggested_h(cloud);
  double crease_deg[3] = {};
  for (const SurfaceOperator surface : {SurfaceOperator::mls, SurfaceOperator::apss, SurfaceOperator::rimls}) {
    RayPssParams params = RayPssParams::from_h(h);
    params.projection.surface = surface;
    const test::CreaseTruth t =
        test::against_bored_box(test::render_at_160(cloud, params, Backend::cpu, cloud.bounds(), 30, 35), box, 0.02f, h);
    std::printf("%s: %lld pixels on the box; holes %lld, extra %lld; normals %.2f deg on the faces, %.2f by the creases\n",
                surface_name(surface), (long long)t.data_pixels, (long long)t.holes, (long long)t.extra,
                t.flat_normal_deg, t.crease_normal_deg);
    SCOPED_TRACE(surface_name(surface));
    ASSERT_GT(t.data_pixels, 4000);
    EXPECT_LE(double(t.holes), 0.005 * double(t.data_pixels));
    EXPECT_LE(double(t.extra), 0.01 * double(t.data_pixels));
    EXPECT_LT(t.flat_normal_deg, 1.0);
    crease_deg[int(surface)] = t.crease_normal_deg;
  }
  EXPECT_LT(crease_deg[int(SurfaceOperator::rimls)], 0.5 * crease_deg[int(SurfaceOperator::mls)]);
}

// The same box without its normals: APSS and RIMLS estimate them (each sample's plane, oriented
// along a spanning tree), and keep the faces as with the file's.
TEST(RenderTruth, ABoredBoxWithoutNormalsEstimatesThem) {
  const test::BoredBox box;
  PointCloud cloud = test::sample(box, 0.03f);
  cloud.normals.clear();
  const float h = test::suggested_h(cloud);
  for (const SurfaceOperator surface : {SurfaceOperator::apss, SurfaceOperator::rimls}) {
    RayPssParams params = RayPssParams::from_h(h);
    params.projection.surface = surface;
    const test::CreaseTruth t =
        test::against_bored_box(test::render_at_160(cloud, params, Backend::cpu, cloud.bounds(), 30, 35), box, 0.02f, h);
    std::printf("%s, estimated normals: holes %lld, extra %lld of %lld; normals %.2f deg on the faces\n",
                surface_name(surface), (long long)t.holes, (long long)t.extra, (long long)t.data_pixels,
                t.flat_normal_deg);
    SCOPED_TRACE(surface_name(surface));
    ASSERT_GT(t.data_pixels, 4000);
    EXPECT_LE(double(t.holes), 0.005 * double(t.data_pixels));
    EXPECT_LE(double(t.extra), 0.01 * double(t.data_pixels));
    EXPECT_LT(t.flat_normal_deg, 1.0);
  }
}

}  // namespace
}  // namespace pss
