// Marching primary rays through analytic volumes (§5.1): hits on the iso-surface or the
// maximal-gradient surface, normals, noise against a marching-tetrahedra mesh, anisotropic
// spacing, an empty volume, a grazing ray; and `pss extract`'s point set.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <string>
#include <tuple>

#include "pss/core/error.hpp"
#include "pss/io/ply.hpp"
#include "pss/render/camera.hpp"
#include "pss/volume/extract.hpp"
#include "support/cli.hpp"
#include "support/marching_tetrahedra.hpp"
#include "support/volume_checks.hpp"
#include "support/volumes.hpp"

namespace pss {
namespace {

using test::Field;
using namespace test;

// A float distance field: |∇f| = 1, so θ1's k is one voxel and the analysis of
// tests/volume_projection_test applies: the fit's lattice noise is about the shell
// thickness k/√2 over √(voxels in the disc of radius 1.5h) ≈ 0.7/√28 ≈ 0.13 voxels rms at
// worst, and a hit is within ε = 0.1 of its projection: rms 0.1, max 0.35 voxels.
TEST(VolumeRender, SphereDistanceFieldHitsLieOnTheSphere) {
  const Field f = test::sphere_distance(vec3(20.0f), 11.0f);
  test::SampleVolumeOptions o;
  o.dims = ivec3(40);
  const Volume volume = test::sample_volume(f, o);
  // 97 %: silhouette rays may miss.
  for (VolumeMethod m : {VolumeMethod::predictor, VolumeMethod::predictor_corrector})
    expect_surface("sphere float, method " + std::to_string(int(m)), f, volume, render(volume, 0.0f, m),
                   {97, 0.1, 0.35, 4.0});
}

// 8 bits: f = 128 − 20·d quantised, so rounding adds a uniform error of ±0.5/20 = 0.025
// voxels to each voxel, negligible beside the fit's lattice noise: same bounds as float.
TEST(VolumeRender, TorusUint8HitsLieOnTheTorus) {
  const Field f = test::torus_distance(vec3(23.5f, 23.5f, 23.5f), 12.0f, 5.0f);
  test::SampleVolumeOptions o;
  o.dims = ivec3(48);
  o.quantize = true;
  o.scale = -20;
  o.offset = 128;
  const Volume volume = test::sample_volume(f, o);
  expect_surface("torus uint8", f, volume, render(volume, 128.0f, VolumeMethod::predictor_corrector),
                 {95, 0.1, 0.4, 5.0});
}

// Gaussian blobs: the iso-surface is not a distance field, so distances are measured to
// first order, |f − v|/|∇f|; its curvature radius is ≥ 4 voxels here, so the quadratic
// over the disc of radius 3 misses it by up to r⁴/(8R³)·... ≈ 0.1 voxels: bounds loosened
// by that.
TEST(VolumeRender, GaussianBlobsIsoSurface) {
  const Field f = test::gaussian_blobs({{vec3(18, 22, 20), 1.0f, 8.0f}, {vec3(28, 20, 22), 0.8f, 6.0f},
                                        {vec3(22, 30, 18), 0.7f, 6.0f}},
                                       0.3f);
  test::SampleVolumeOptions o;
  o.dims = ivec3(44);
  const Volume volume = test::sample_volume(f, o);
  expect_surface("blobs", f, volume, render(volume, 0.3f, VolumeMethod::predictor_corrector), {95, 0.15, 0.5, 6.0});
}

// Gradient mode (θ2): a smooth indicator 255/(1 + e^(d/1.5)) has its largest |∇f| on the
// sphere d = 0. The θ2 ridge is symmetric about it to first order; its curvature shifts
// the weighted centre by about width²/R ≈ 0.2 voxels: rms 0.3, max 0.6. The ridge is
// about twice as thick as θ1's shell (θ2 halves at |d| ≈ 1.3), and so is the lattice noise
// of the normals: rms 8°.
// The sphere of radius 11 about (20, 20, 20) as 255/(1 + e^(d/width)) in 40³ voxels of 8 bits.
Volume smooth_sphere(float width) {
  test::SampleVolumeOptions o;
  o.dims = ivec3(40);
  o.quantize = true;
  return test::sample_volume(test::smooth_indicator(test::sphere_distance(vec3(20.0f), 11.0f), 255.0f, width), o);
}

TEST(VolumeRender, SmoothIndicatorMaximalGradientSurface) {
  const Field sphere = test::sphere_distance(vec3(20.0f), 11.0f);
  const Volume volume = smooth_sphere(1.5f);
  expect_surface("gradient mode", sphere, volume, render(volume, std::nullopt, VolumeMethod::predictor_corrector),
                 {95, 0.3, 0.6, 8.0});
}

// A step sharper than a voxel (width 0.3): its ridge of θ2 above the threshold is thinner
// than the step b = 1.5 voxels between a ray's samples. The paper's test, θ2 above the
// threshold at the sample, let most rays step over it (terraces on the tooth); every sample
// within b/2 of a cell above it is projected, and the rays find the sphere as the iso-surface's do.
TEST(VolumeRender, AGradientRidgeThinnerThanTheStepIsFound) {
  const Field sphere = test::sphere_distance(vec3(20.0f), 11.0f);
  const Volume volume = smooth_sphere(0.3f);
  const Rendered gradient = render(volume, std::nullopt, VolumeMethod::predictor_corrector);
  const Rendered iso = render(volume, 127.5f, VolumeMethod::predictor_corrector);
  std::printf("thin ridge: %zu gradient hits, %zu iso hits\n", gradient.hits.size(), iso.hits.size());
  EXPECT_GT(double(gradient.hits.size()), 0.95 * double(iso.hits.size()));
  const Accuracy a = measure(sphere, gradient.hits);
  EXPECT_LT(a.rms_distance, 0.3);
}

// Noise σ = 0.4 voxels (a float distance field plus Gaussian noise; an 8-bit torus at 20
// per voxel plus noise of σ = 8): a mesh vertex interpolated on one edge inherits about σ
// of it, a central-difference normal σ/√2 per component over |∇f| = 1, ~20°. The PSS
// averages some 30 voxels' worth: it must be markedly better in both, and the corrector
// no worse than the predictor.
TEST(VolumeRender, NoisyVolumesBeatMarchingTetrahedra) {
  struct Case {
    const char* name;
    Field field;
    test::SampleVolumeOptions options;
    float iso;
  };
  test::SampleVolumeOptions sphere_options;
  sphere_options.dims = ivec3(40);
  sphere_options.noise = 0.4f;
  test::SampleVolumeOptions torus_options;
  torus_options.dims = ivec3(48);
  torus_options.noise = 8.0f;
  torus_options.quantize = true;
  torus_options.scale = -20;
  torus_options.offset = 128;
  const Case cases[] = {{"float sphere", test::sphere_distance(vec3(20.0f), 11.0f), sphere_options, 0.0f},
                        {"uint8 torus", test::torus_distance(vec3(23.5f), 12.0f, 5.0f), torus_options, 128.0f}};
  for (const Case& c : cases) {
    const Volume volume = test::sample_volume(c.field, c.options);
    std::vector<std::pair<vec3, vec3>> mesh;
    // Noise makes small closed bubbles away from the surface too; only the surface's own
    // vertices are compared (within 2 voxels of it).
    for (const test::MeshVertex& v : test::marching_tetrahedra_vertices(volume.view(), c.iso))
      if (c.field.distance(v.point) < 2.0f) mesh.emplace_back(v.point, v.normal);
    const Accuracy mt = measure(c.field, mesh);
    const Accuracy p = measure(c.field, render(volume, c.iso, VolumeMethod::predictor).hits);
    const Accuracy pc = measure(c.field, render(volume, c.iso, VolumeMethod::predictor_corrector).hits);
    std::printf("noisy %s: mesh rms %.3f voxels %.2f deg; predictor rms %.3f %.2f deg; predictor-corrector rms %.3f "
                "%.2f deg\n", c.name, mt.rms_distance, mt.rms_normal_deg, p.rms_distance, p.rms_normal_deg,
                pc.rms_distance, pc.rms_normal_deg);
    EXPECT_LT(pc.rms_distance, 0.5 * mt.rms_distance) << c.name;
    EXPECT_LT(pc.rms_normal_deg, 0.5 * mt.rms_normal_deg) << c.name;
    // "At least as accurate", within the lattice noise of one configuration (0.01 voxels).
    EXPECT_LT(pc.rms_distance, p.rms_distance + 0.01) << c.name;
  }
}

// A wider support averages more noise: h = 4 voxels (N(x) of radius 6 voxels, up to 1,360
// voxels, which a buffer of 512 refused) on the noisy sphere above. Each projection fits a
// disc of radius 6 instead of 3: four times the voxels, over twice the lever for the
// normal (measured: 1.3° rms against 5.5°, 0.08 voxels against 0.12), and the quadratic
// still fits a sphere of radius 11 (it misses it by ρ⁴/(8R³) ≈ 0.1 voxels at the rim, less
// at the centre). A neighbourhood cut to its first 512 voxels in the lattice's order would
// fit one side of the ball only.
TEST(VolumeRender, AWiderSupportAveragesMoreNoise) {
  const Field f = test::sphere_distance(vec3(20.0f), 11.0f);
  test::SampleVolumeOptions o;
  o.dims = ivec3(40);
  o.noise = 0.4f;
  const Volume volume = test::sample_volume(f, o);
  const Accuracy narrow = measure(f, render(volume, 0.0f, VolumeMethod::predictor_corrector).hits);
  const Rendered wide_render = render(volume, 0.0f, VolumeMethod::predictor_corrector, 4.0f);
  const Accuracy wide = measure(f, wide_render.hits);
  std::printf("noisy sphere: h = 2 rms %.3f voxels %.2f deg; h = 4 rms %.3f voxels %.2f deg, %zu hits\n",
              narrow.rms_distance, narrow.rms_normal_deg, wide.rms_distance, wide.rms_normal_deg,
              wide_render.hits.size());
  EXPECT_GT(wide_render.hits.size(), 0.9 * double(render(volume, 0.0f, VolumeMethod::predictor).hits.size()));
  EXPECT_LT(wide.rms_normal_deg, 0.5 * narrow.rms_normal_deg);
  EXPECT_LT(wide.rms_distance, narrow.rms_distance);
}

// Spacing 1 × 1 × 2.5: positions, gradients and neighbourhoods are in world units, so the
// sphere (radius 10 world units) is found as in the isotropic case; the coarse z axis
// (2.5 units per voxel) loosens the bounds to the z voxel: rms 0.25, max 0.8 world units.
TEST(VolumeRender, AnisotropicSpacing) {
  const Field f = test::sphere_distance(vec3(16.0f, 16.0f, 17.5f), 10.0f);
  test::SampleVolumeOptions o;
  o.dims = ivec3(33, 33, 15);
  o.spacing = vec3(1.0f, 1.0f, 2.5f);
  const Volume volume = test::sample_volume(f, o);
  // Normals: 2.5× coarser in z, so the normal noise grows with it.
  expect_surface("anisotropic", f, volume, render(volume, 0.0f, VolumeMethod::predictor_corrector, 2.0f),
                 {90, 0.25, 0.8, 12.0});
}

TEST(VolumeRender, NothingPassesTheThresholdGivesAnEmptyImage) {
  const Field f = test::sphere_distance(vec3(12.0f), 6.0f);
  test::SampleVolumeOptions o;
  o.dims = ivec3(24);
  const Volume volume = test::sample_volume(f, o);
  const Rendered r = render(volume, 1000.0f, VolumeMethod::predictor_corrector);  // above every value
  EXPECT_TRUE(r.hits.empty());
  EXPECT_EQ(r.frame.image.pixels.size(), std::size_t(64 * 64));
}

// A ray tangent to the sphere, and rays just inside and outside it: the tangent ray may
// hit or miss (the surface is only known to ~0.1 voxels), but any hit must lie on the
// sphere; a ray 0.5 voxels inside must hit, one 1 voxel outside must not.
TEST(VolumeRender, GrazingRays) {
  const vec3 c(20.0f);
  const float radius = 11.0f;
  const Field f = test::sphere_distance(c, radius);
  test::SampleVolumeOptions o;
  o.dims = ivec3(40);
  const PreparedVolume prepared = test::prepare_iso(test::sample_volume(f, o), 0.0f);
  const VolumeFinder finder{prepared.scene()};
  const auto ray_at = [&](float offset) { return Ray{c + vec3(-30.0f, radius + offset, 0.0f), vec3(1, 0, 0)}; };
  const Hit tangent = finder.primary(ray_at(0.0f));
  if (tangent.found()) EXPECT_LT(f.distance(tangent.point), 0.35f);
  const Hit inside = finder.primary(ray_at(-0.5f));
  ASSERT_TRUE(inside.found());
  EXPECT_LT(f.distance(inside.point), 0.35f);
  EXPECT_FALSE(finder.primary(ray_at(1.0f)).found());
}

// A neighbourhood radius whose ball could hold more voxels than the kernels' buffer is
// refused before any work: a gather must never stop early and silently drop voxels.
TEST(VolumeRender, RadiusBeyondTheNeighbourhoodCapacityIsAnError) {
  test::SampleVolumeOptions o;
  o.dims = ivec3(16);
  // Radius 10 voxels: (10 + 0.87)³·4π/3 ≈ 5380 voxels > kMaxNeighbours (4096).
  const VolumeParams params = VolumeParams::from_voxels(1.0f, VolumeMethod::predictor_corrector, 4.0f, 0.75f, 0.9f,
                                                        0.1f, 10.0f);
  ASSERT_GT(neighbourhood_bound(params.radius, VolumeView{}), float(kMaxNeighbours));
  const Volume volume = test::sample_volume(test::sphere_distance(vec3(8.0f), 5.0f), o);
  EXPECT_THROW(test::prepare_iso(volume, 0.0f, params), Error);
  // Radius 9 voxels, h = 6 at the default radius 1.5h, is taken (--radius's help).
  const VolumeParams widest = VolumeParams::from_voxels(1.0f, VolumeMethod::predictor_corrector, 6.0f, 0.75f, 0.9f,
                                                        0.1f, 9.0f);
  EXPECT_NO_THROW(test::prepare_iso(volume, 0.0f, widest));
}

// Empty-space skipping changes the speed only: with every brick marked occupied the rays
// visit every sample, and the hits are the same, bit for bit.
// A noisy torus, and a plane just past a brick's face (x = 8.3: the cells it crosses lie in
// the second brick, the samples that first reach it in the first), seen from both sides.
TEST(VolumeRender, BrickSkippingKeepsTheHits) {
  test::SampleVolumeOptions torus_options;
  torus_options.dims = ivec3(48);
  torus_options.noise = 0.3f;
  test::SampleVolumeOptions plane_options;
  plane_options.dims = ivec3(24);
  const Field plane{[](vec3 p) { return p.x - 8.3f; }, [](vec3) { return vec3(1, 0, 0); }, 0.0f};
  const std::pair<Volume, CameraSettings> scenes[] = {
      {test::sample_volume(test::torus_distance(vec3(23.5f), 12.0f, 5.0f), torus_options), {40, 40, 30, 20, 35}},
      {test::sample_volume(plane, plane_options), {40, 40, -90, 10, 35}},
      {test::sample_volume(plane, plane_options), {40, 40, 90, 10, 35}}};
  for (const auto& [volume, view] : scenes) {
    const PreparedVolume prepared = test::prepare_iso(volume, 0.0f);
    ASSERT_LT(prepared.bricks.occupied_count, std::int64_t(prepared.bricks.occupied.size()));
    BrickGrid all = prepared.bricks;
    std::fill(all.occupied.begin(), all.occupied.end(), std::uint8_t(1));
    VolumeScene skipping = prepared.scene(), exhaustive = prepared.scene();
    exhaustive.bricks = all.view();
    const Camera camera = Camera::framing(prepared.fields.volume.view().bounds(), view);
    int hits = 0;
    for (int y = 0; y < camera.height; ++y)
      for (int x = 0; x < camera.width; ++x) {
        const Ray ray = camera.primary_ray(x, y);
        const Hit a = march_volume(skipping, ray), b = march_volume(exhaustive, ray);
        ASSERT_EQ(a.found(), b.found()) << view.azimuth_deg;
        if (!a.found()) continue;
        ++hits;
        EXPECT_EQ(a.t, b.t) << view.azimuth_deg;
        EXPECT_EQ(a.normal, b.normal) << view.azimuth_deg;
      }
    EXPECT_GT(hits, 100) << view.azimuth_deg;
  }
}

// The marcher as it was before the predictor could stop early: the paper's march (§5.1)
// with our fragment and data-surface tests and retry cap, and no shortcut but the
// corrector's reach. Every sample that passes the fragment test is projected with the
// predictor run to convergence; accepted within ε, or followed to the ray's intersection
// with the polynomial inside B(r, b).
Hit uninterrupted_march(const VolumeScene& s, const Ray& ray) {
  const VolumeParams& p = s.params;
  Hit hit;
  float t0, t1;
  if (!clip_to_box(ray, s.fields.volume.bounds(), t0, t1)) return hit;
  VoxelNeighbourhood nb;
  for (float j = 0; j <= (t1 - t0) / p.step; j += 1) {
    const float t_sample = t0 + j * p.step;
    const vec3 r = ray.at(t_sample);
    if (!passes_feature_test(s.fields, s.cells, s.feature, r, p.sample_reach())) continue;
    float t = t_sample;
    for (int attempt = 0; attempt <= p.max_retries; ++attempt) {
      const vec3 x = ray.at(t);
      VolumeProjection proj = predict(s.fields, p, x, nb);
      if (proj.status != VolumeProjectionStatus::ok) break;
      if (p.method == VolumeMethod::predictor_corrector &&
          length2(proj.point - x) <= kCorrectorReach * kCorrectorReach * p.epsilon * p.epsilon) {
        proj = correct(s.fields, p, proj, nb);
        if (proj.status != VolumeProjectionStatus::ok) break;
      }
      if (length2(proj.point - x) <= p.epsilon * p.epsilon) {
        if (!is_data_surface(s.fields, s.cells, s.feature, x, proj.normal, p.surface_reach())) break;
        hit.t = t;
        hit.point = x;
        hit.normal = proj.normal;
        hit.flags = kHitFound;
        return hit;
      }
      t = intersection_in_ball(proj, ray, t, r, p.step);
      if (!(t < kInfinity)) break;
    }
  }
  return hit;
}

// The marcher's shortcut (the predictor stopped early) decides only some rejections on an
// unconverged polynomial: nearly every hit is the uninterrupted march's own, to rounding;
// where a sample was rejected so, the ray's next sample finds the same surface within 2ε,
// or (on a silhouette) none. No hit is new. And every hit is the paper's projection of its
// point within ε: projected again in full, it lands within ε, with the hit's normal.
TEST(VolumeRender, HitsAreThoseOfTheUninterruptedMarch) {
  test::SampleVolumeOptions o;
  o.dims = ivec3(40);
  o.noise = 0.2f;
  const Volume volume = test::sample_volume(test::torus_distance(vec3(19.5f), 10.0f, 4.5f), o);
  for (VolumeMethod m : {VolumeMethod::predictor, VolumeMethod::predictor_corrector}) {
    const PreparedVolume prepared = test::prepare_iso(volume, 0.0f, VolumeParams::from_voxels(1.0f, m));
    const VolumeScene scene = prepared.scene();
    const Camera camera = Camera::framing(prepared.surface_bounds(), {48, 48, 30, 20, 35});
    VoxelNeighbourhood nb;
    int hits = 0, moved = 0, lost = 0;
    for (int y = 0; y < camera.height; ++y)
      for (int x = 0; x < camera.width; ++x) {
        const Ray ray = camera.primary_ray(x, y);
        const Hit hit = march_volume(scene, ray), uninterrupted = uninterrupted_march(scene, ray);
        if (!hit.found()) {
          lost += uninterrupted.found();
          continue;
        }
        ++hits;
        ASSERT_TRUE(uninterrupted.found()) << int(m);
        const bool same = std::abs(hit.t - uninterrupted.t) <= 1e-4f && glm::length(hit.normal - uninterrupted.normal) <= 1e-4f;
        moved += !same;
        if (!same) EXPECT_LE(std::abs(hit.t - uninterrupted.t), 2 * scene.params.epsilon) << int(m);
        const VolumeProjection full = project_volume_point(scene.fields, scene.params, hit.point, nb);
        ASSERT_EQ(full.status, VolumeProjectionStatus::ok);
        EXPECT_LE(glm::length(full.point - hit.point), scene.params.epsilon * 1.0001f) << int(m);
        EXPECT_LT(glm::length(full.normal - hit.normal), 1e-4f) << int(m);
      }
    std::printf("method %d: %d hits, %d moved from and %d lost of the uninterrupted march's\n", int(m), hits, moved, lost);
    EXPECT_GT(hits, 500) << int(m);
    EXPECT_LE(moved + lost, hits / 100) << int(m);  // measured: none
  }
}

// --debug-projection (the paper's Figure 2): the first sample on a ray lies up to b from
// the surface, so the predictor moves most of them farther than ε (red); painted pixels
// keep the shading's brightness in one hue.
TEST(VolumeRender, DebugProjectionMarksPredictorMoves) {
  const Field f = test::sphere_distance(vec3(16.0f), 9.0f);
  test::SampleVolumeOptions o;
  o.dims = ivec3(32);
  VolumeParams params = VolumeParams::from_voxels(1.0f);
  params.debug_projection = true;
  const PreparedVolume prepared = test::prepare_iso(test::sample_volume(f, o), 0.0f, params);
  Stats stats;
  const Camera camera = Camera::framing(prepared.fields.volume.view().bounds(), {48, 48, 0, 0, 35});
  RenderedFrame frame = render_volume(prepared, camera, TraceSettings{}, Backend::cpu, stats);
  paint_debug_projection(frame);
  std::size_t hits = 0, red = 0;
  for (std::size_t i = 0; i < frame.hits.size(); ++i) {
    if (!frame.hits[i].found()) continue;
    ++hits;
    const vec3 c = frame.image.pixels[i];
    if (frame.hits[i].flags & kHitPredictorMoved && !(frame.hits[i].flags & kHitCorrectorMoved)) {
      ++red;
      EXPECT_GT(c.r, 4 * c.g);
    }
  }
  EXPECT_GT(red, hits / 2);
}

// `pss extract`: points on the surface with the accuracy of the hits, normals along the
// sphere's, and about one per b-cell: a sphere of radius R has area 4πR², so about
// 4πR²/b² cells at the grid's density, within a factor 2 (cells are cut obliquely).
TEST(VolumeExtract, SpherePointsAreOnTheSurfaceAndThinned) {
  const vec3 c(16.0f);
  const float radius = 9.0f;
  const Field f = test::sphere_distance(c, radius);
  test::SampleVolumeOptions o;
  o.dims = ivec3(32);
  o.noise = 0.2f;
  const PreparedVolume prepared = test::prepare_iso(test::sample_volume(f, o), 0.0f);
  const VolumeParams& params = prepared.params;
  Stats stats;
  ExtractionCounts counts;
  const PointCloud cloud = extract_surface(prepared, Backend::cpu, stats, counts);
  std::vector<std::pair<vec3, vec3>> points;
  for (std::size_t i = 0; i < cloud.size(); ++i) points.emplace_back(cloud.positions[i], cloud.normals[i]);
  const Accuracy a = measure(f, points);
  const double cells = 4 * 3.14159 * radius * radius / (params.step * params.step);
  std::printf("extract: %zu points (%.0f cells), rms %.3f max %.3f voxels, normals rms %.2f deg\n", cloud.size(),
              cells, a.rms_distance, a.max_distance, a.rms_normal_deg);
  EXPECT_GT(double(cloud.size()), 0.5 * cells);
  EXPECT_LT(double(cloud.size()), 2.0 * cells);
  EXPECT_LT(a.rms_distance, 0.15);
  EXPECT_LT(a.max_distance, 0.5);
  EXPECT_LT(a.rms_normal_deg, 5.0);
  // Normals point along ∇f, outward for a distance field.
  for (std::size_t i = 0; i < cloud.size(); ++i) EXPECT_GT(glm::dot(cloud.normals[i], f.normal(cloud.positions[i])), 0.0f);
  // The candidates' lattice spans the box, its last layer within a step of the far side, and
  // the points kept are one a cell of side b.
  const ExtractLattice lattice = extraction_lattice(prepared.scene());
  const Aabb box = prepared.scene().fields.volume.bounds();
  for (int a = 0; a < 3; ++a) {
    const float last = lattice.origin[a] + float(lattice.dims[a] - 1) * lattice.spacing;
    EXPECT_LE(last, box.hi[a]) << a;
    EXPECT_GT(last, box.hi[a] - lattice.spacing) << a;
  }
  const auto cell_of = [&](vec3 p) {
    const vec3 c = glm::floor((p - lattice.origin) / lattice.spacing);
    return std::tuple<int, int, int>(int(c.x), int(c.y), int(c.z));
  };
  std::set<std::tuple<int, int, int>> occupied;
  for (const vec3& p : cloud.positions) EXPECT_TRUE(occupied.insert(cell_of(p)).second) << "two points in one cell";
  // Each is the accepted candidate of its cell that moved least, the first in the lattice's
  // order on a tie: every candidate projected here, one by one (this build's arithmetic, not
  // the kernel's AVX2 copy: within rounding; two candidates of a cell lie far further apart).
  std::map<std::tuple<int, int, int>, ExtractedPoint> least;
  for (std::int64_t i = 0; i < lattice.size(); ++i) {
    const ExtractedPoint e = extract_candidate(prepared.scene(), lattice.at(i));
    if (!(e.moved < kInfinity)) continue;
    const auto [at, inserted] = least.try_emplace(cell_of(e.point), e);
    if (!inserted && e.moved < at->second.moved) at->second = e;
  }
  ASSERT_EQ(least.size(), cloud.size());
  for (const vec3& p : cloud.positions) EXPECT_LT(glm::length(least.at(cell_of(p)).point - p), 1e-4f);
}

}  // namespace
}  // namespace pss

namespace pss {
namespace {

// The command lines on a float32 raw sphere: `pss volume --hits` and
// `pss extract` write points on the sphere in world coordinates (origin 0, spacing from
// --spacing), and `pss render` ray traces the extracted set (the paper's Figure 5 flow).
TEST(VolumeCli, HitsAndExtractionOnARawFloatSphere) {
  namespace fs = std::filesystem;
  const test::TestFolder folder;
  const fs::path& d = folder.path();
  const Field f = test::sphere_distance(vec3(16.0f, 16.0f, 24.0f), 10.0f);
  test::SampleVolumeOptions o;
  o.dims = ivec3(32, 32, 24);
  o.spacing = vec3(1.0f, 1.0f, 2.0f);
  const Volume v = test::sample_volume(f, o);
  {
    std::ofstream out(d / "sphere.raw", std::ios::binary);
    out.write(reinterpret_cast<const char*>(v.values.data()), std::streamsize(v.values.size() * sizeof(float)));
  }
  const std::string input = (d / "sphere.raw").string() + " --dims 32x32x24 --type float32 --spacing 1,1,2 --iso 0";
  const std::string cli = PSS_CLI;
  ASSERT_EQ(std::system((cli + " volume " + input + " -o " + (d / "s.png").string() + " --size 48x48 --hits " +
                         (d / "hits.ply").string() + " --stats " + (d / "s.json").string() + " > /dev/null")
                            .c_str()),
            0);
  ASSERT_EQ(std::system((cli + " extract " + input + " -o " + (d / "surface.ply").string() + " > /dev/null").c_str()), 0);
  ASSERT_EQ(std::system((cli + " render " + (d / "surface.ply").string() + " -o " + (d / "r.png").string() +
                         " --size 32x32 > /dev/null")
                            .c_str()),
            0);
  EXPECT_TRUE(fs::exists(d / "s.png") && fs::exists(d / "s.json") && fs::exists(d / "r.png"));
  for (const char* name : {"hits.ply", "surface.ply"}) {
    const PointCloud cloud = read_ply(d / name);
    ASSERT_GT(cloud.size(), 100u) << name;
    ASSERT_TRUE(cloud.has_normals()) << name;
    std::vector<std::pair<vec3, vec3>> points;
    for (std::size_t i = 0; i < cloud.size(); ++i) points.emplace_back(cloud.positions[i], cloud.normals[i]);
    const Accuracy a = measure(f, points);
    // The anisotropic bounds of VolumeRender.AnisotropicSpacing (z spacing 2 here).
    EXPECT_LT(a.rms_distance, 0.25) << name;
    EXPECT_LT(a.max_distance, 0.8) << name;
    EXPECT_LT(a.rms_normal_deg, 12.0) << name;
  }
}

}  // namespace
}  // namespace pss
