// The CUDA renderer runs the same kernels as the CPU: hits and image agree to rounding.
// Skips cleanly on machines without a device (CI).
#include <gtest/gtest.h>

#include <cstdlib>

#include "pss/points/render_cloud.hpp"
#include "pss/render/frame_outputs.hpp"
#include "support/render_truth.hpp"
#include "support/shapes.hpp"

namespace pss {
namespace {

PointCloud noisy_torus() {
  test::SampleOptions o;
  o.count = 12000;
  o.noise = 0.005f * test::Torus{}.minor;
  return test::sample(test::Torus{}, o);
}

// The cloud rendered on both backends, prepared on each (the GPU's preprocessing on the
// device), with shadows and reflections; hits and image compared.
void expect_backends_agree(const PointCloud& cloud, SurfaceColor color,
                           SurfaceOperator surface = SurfaceOperator::mls) {
  const float h = test::suggested_h(cloud);
  RayPssParams params = RayPssParams::from_h(h);
  params.projection.surface = surface;
  CameraSettings view;
  view.width = view.height = 128;
  view.azimuth_deg = 20;
  view.elevation_deg = 35;
  const Camera camera = Camera::framing(cloud.bounds(), view);
  TraceSettings settings;
  settings.shading = ShadingParams::for_camera(camera);
  settings.shadows = settings.reflections = true;
  Stats stats;
  const PreparedCloud on_cpu(cloud, params, Backend::cpu, stats, color);
  const PreparedCloud on_gpu(cloud, params, Backend::cuda, stats, color);
  const RenderedFrame cpu = render_cloud(on_cpu, camera, settings, Backend::cpu, stats);
  const RenderedFrame gpu = render_cloud(on_gpu, camera, settings, Backend::cuda, stats);

  // The device contracts a·b + c into FMAs: a few ulps, which can flip a ray that grazes a
  // ball or the ε test in a handful of pixels; elsewhere the hits agree far below h.
  std::size_t flipped = 0, far = 0, pixels_off = 0;
  for (std::size_t i = 0; i < cpu.hits.size(); ++i) {
    if (cpu.hits[i].found() != gpu.hits[i].found()) {
      ++flipped;
      continue;
    }
    if (cpu.hits[i].found() && glm::length(cpu.hits[i].point - gpu.hits[i].point) > 1e-3f * h) ++far;
    const vec3 d = glm::abs(cpu.image.pixels[i] - gpu.image.pixels[i]);
    if (glm::max(d.x, glm::max(d.y, d.z)) > 2.0f / 255) ++pixels_off;
  }
  EXPECT_LE(flipped, cpu.hits.size() / 200);
  EXPECT_LE(far, cpu.hits.size() / 200);
  EXPECT_LE(pixels_off, cpu.hits.size() / 100);
}

TEST(GpuRender, MatchesCpu) {
  if (cuda::device_count() == 0) GTEST_SKIP() << "no CUDA device";
  expect_backends_agree(noisy_torus(), SurfaceColor::albedo);
}

// APSS and RIMLS (issue 26): the samples' normals estimated and oriented on each backend,
// then the same kernels.
TEST(GpuRender, EverySurfaceMatchesCpu) {
  if (cuda::device_count() == 0) GTEST_SKIP() << "no CUDA device";
  for (SurfaceOperator surface : {SurfaceOperator::apss, SurfaceOperator::rimls}) {
    SCOPED_TRACE(surface_name(surface));
    expect_backends_agree(noisy_torus(), SurfaceColor::albedo, surface);
  }
}

// Issue 26's noise and outliers on the device: a noisy sphere with 1 % strays is the sphere
// for every surface kind, within the CPU test's budgets (tests/render_truth_test.cpp), and
// the strays set aside on the device are those set aside on the CPU, within a few.
TEST(GpuRender, NoisySphereWithStraysIsTheSphereForEverySurface) {
  if (cuda::device_count() == 0) GTEST_SKIP() << "no CUDA device";
  const PointCloud cloud = test::noisy_sphere_with_strays(12000, 0.5f, 0.01f);
  for (const SurfaceOperator surface : {SurfaceOperator::mls, SurfaceOperator::apss, SurfaceOperator::rimls}) {
    const test::RenderTruth gpu = test::render_sphere(cloud, surface, OutlierPolicy::set_aside, Backend::cuda);
    test::expect_like_the_sphere(gpu, surface_name(surface));
    const test::RenderTruth cpu = test::render_sphere(cloud, surface, OutlierPolicy::set_aside, Backend::cpu);
    EXPECT_LE(std::abs(gpu.holes - cpu.holes), 3) << surface_name(surface);
    EXPECT_LE(std::abs(gpu.extra - cpu.extra), 3) << surface_name(surface);
    EXPECT_NEAR(gpu.mean_distance, cpu.mean_distance, 1e-4) << surface_name(surface);
  }
}

// `--borders clip` on the device (tests/borders_test.cpp): an open square ends at its samples,
// whole inside; extended, it runs on past them as on the CPU.
TEST(GpuRender, AnOpenSquareEndsAtItsSamplesWhenClipped) {
  if (cuda::device_count() == 0) GTEST_SKIP() << "no CUDA device";
  const test::BorderTruth clip = test::render_open_square(BorderMode::clip, SurfaceOperator::mls, Backend::cuda);
  const test::BorderTruth extend = test::render_open_square(BorderMode::extend, SurfaceOperator::mls, Backend::cuda);
  ASSERT_GT(clip.inner_pixels, 6000);
  EXPECT_EQ(clip.holes, 0);
  EXPECT_LT(clip.overshoot, 0.25);
  EXPECT_GT(extend.beyond, 200);
}

// FrameHits::summary on the device: the hits' counts come back (HitCountsKernel), not the hits.
TEST(GpuRender, AFrameWithoutItsHitsHasTheirCounts) {
  if (cuda::device_count() == 0) GTEST_SKIP() << "no CUDA device";
  const PointCloud cloud = noisy_torus();
  Stats stats;
  const PreparedCloud prepared(cloud, RayPssParams::from_h(test::suggested_h(cloud)), Backend::cuda, stats);
  CameraSettings view;
  view.width = view.height = 96;
  const Camera camera = Camera::framing(cloud.bounds(), view);
  const TraceSettings settings = TraceSettings::for_camera(camera, true, true);
  const RenderedFrame all = render_cloud(prepared, camera, settings, Backend::cuda, stats);
  const RenderedFrame counted = render_cloud(prepared, camera, settings, Backend::cuda, stats, FrameHits::summary);
  EXPECT_TRUE(counted.hits.empty());
  EXPECT_EQ(counted.image.pixels, all.image.pixels);
  std::int64_t hits = 0, converged = 0, capped = 0, iterations = 0;  // from the hits themselves
  for (const Hit& h : all.hits) {
    iterations += h.iterations;
    hits += h.found();
    converged += h.found() && (h.flags & kHitConverged);
    capped += h.found() && (h.flags & kHitCapped);
  }
  const FrameSummary c = summarize(counted);
  EXPECT_GT(hits, 100);
  EXPECT_EQ(c.hits, hits);
  EXPECT_EQ(c.converged, converged);
  EXPECT_EQ(c.capped, capped);
  EXPECT_EQ(c.iterations, iterations);
  EXPECT_EQ(c.secondary_rays, all.secondary_rays);
}

// --color: the colours reach the device in the grid's order and interpolate as on the CPU.
TEST(GpuRender, ColoursMatchCpu) {
  if (cuda::device_count() == 0) GTEST_SKIP() << "no CUDA device";
  PointCloud cloud = noisy_torus();
  for (const vec3& p : cloud.positions) cloud.colors.push_back(p.x > 0 ? Rgb8(230, 40, 20) : Rgb8(20, 60, 240));
  expect_backends_agree(cloud, SurfaceColor::samples);
}

}  // namespace
}  // namespace pss
