// The predictor (Eq. 3) and corrector (Eq. 4) on analytic volumes, and the test that
// decides the form of θ1 (docs/paper-notes.md, §4).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "pss/volume/fields.hpp"
#include "pss/volume/projection.hpp"
#include "pss/volume/surface_cells.hpp"
#include "support/volumes.hpp"

namespace pss {

using test::Field;

// Points within `spread` of the surface of a sphere of radius R about c.
std::vector<vec3> points_near_sphere(vec3 c, float radius, float spread, int count, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<float> gauss;
  std::uniform_real_distribution<float> offset(-spread, spread);
  std::vector<vec3> out;
  for (int i = 0; i < count; ++i) {
    const vec3 d = glm::normalize(vec3(gauss(rng), gauss(rng), gauss(rng)));
    out.push_back(c + (radius + offset(rng)) * d);
  }
  return out;
}

struct Errors {
  float max_distance = 0, rms_distance = 0, max_normal_deg = 0;
  int failed = 0;
};

Errors project_all(const VolumeFields& fields, const FeatureParams& feature, const VolumeParams& params,
                   const Field& truth, const std::vector<vec3>& points) {
  Errors e;
  double sum2 = 0;
  VoxelNeighbourhood nb;
  for (const vec3& r : points) {
    const VolumeProjection p = project_volume_point(fields.view(), params, r, nb);
    if (p.status != VolumeProjectionStatus::ok) {
      ++e.failed;
      continue;
    }
    const float d = truth.distance(p.point);
    e.max_distance = std::max(e.max_distance, d);
    sum2 += double(d) * d;
    const float c = std::abs(glm::dot(p.normal, truth.normal(p.point)));
    e.max_normal_deg = std::max(e.max_normal_deg, std::acos(std::min(1.0f, c)) * 57.2958f);
  }
  e.rms_distance = float(std::sqrt(sum2 / double(points.size() - e.failed)));
  return e;
}

// θ1 decides which voxels the fit of Eq. 3 follows. We give the predictor both forms as
// precomputed weights (through the θ2 channel, whose weight is |g|²/max|g|²: g = n·√θ) on a
// distance-field sphere, and see which one lands on the surface.
TEST(VolumeTheta, ExponentialFormRecoversTheIsoSurfacePrintedFormDoesNot) {
  const vec3 c(16.0f);
  const float radius = 9.0f, k = 1.0f;
  const Field f = test::sphere_distance(c, radius);
  test::SampleVolumeOptions o;
  o.dims = ivec3(32);
  VolumeFields base = compute_fields(test::sample_volume(f, o));

  const auto with_weights = [&](auto theta) {
    VolumeFields w = base;
    set_feature(w, gradient_feature());  // the gradients' directions
    for (std::size_t i = 0; i < w.features.size(); ++i) w.features[i].weight = theta(w.volume.values[i]);
    return w;
  };
  const VolumeFields exp_form = with_weights([&](float v) { return std::exp(-(v * v) / (k * k)); });
  const VolumeFields printed_form = with_weights([&](float v) { return 1 - std::exp(-(v * v) / (k * k)); });

  FeatureParams feature;
  VolumeParams params = VolumeParams::from_voxels(1.0f, VolumeMethod::predictor);
  const auto points = points_near_sphere(c, radius, 1.0f, 200, 3);
  const Errors good = project_all(exp_form, feature, params, f, points);
  const Errors bad = project_all(printed_form, feature, params, f, points);
  std::printf("theta1 exp form: rms %.4f max %.4f; printed 1-exp form: rms %.4f max %.4f voxels\n",
              good.rms_distance, good.max_distance, bad.rms_distance, bad.max_distance);
  // A distance field's voxels weighted by exp(−d²) balance on both sides of the surface:
  // the sampling bias of a Gaussian of width 1 voxel on a unit lattice is ~2e^(−π²) ≈ 1e-4
  // (Poisson summation) and the quadratic misses the sphere by ρ⁴/(8R³) ≈ 0.01 voxels; what
  // remains is lattice noise: the shell of weighted voxels is k/√2 ≈ 0.7 voxels thick, and
  // the disc of radius ρ = 3 holds ~28 voxels per layer, 0.7/√28 ≈ 0.13 voxels at worst.
  EXPECT_EQ(good.failed, 0);
  EXPECT_LT(good.rms_distance, 0.07f);
  EXPECT_LT(good.max_distance, 0.15f);
  // 1 − exp weighs the voxels farthest from the surface most: the fit is pulled ~h away.
  EXPECT_GT(bad.rms_distance, 0.5f);
}

// θ2 per lattice step (theta_gradient): the same values on thick slices, or thin ones, weigh
// every voxel as on a cubic grid, and the ray's feature test agrees at the same lattice
// points. In space, a jump between two slices 6× the pixels apart is 1/6 as steep.
TEST(VolumeTheta, GradientWeightsPerLatticeStepAreThoseOfACubicGrid) {
  test::SampleVolumeOptions o;
  o.dims = ivec3(14, 12, 10);
  o.noise = 1;  // random values: gradients every way
  const Field flat{[](vec3) { return 0.0f; }, [](vec3) { return vec3(0, 0, 1); }};
  const FeatureParams feature = gradient_feature(0.3f);
  const auto fields_at = [&](vec3 spacing) {
    o.spacing = spacing;
    VolumeFields f = compute_fields(test::sample_volume(flat, o));
    set_feature(f, feature);
    return f;
  };
  const VolumeFields cubic = fields_at(vec3(1.0f));
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> along(0.0f, 1.0f);
  for (const vec3 spacing : {vec3(0.5f, 0.5f, 3.0f), vec3(3.0f, 3.0f, 0.5f)}) {
    SCOPED_TRACE(spacing.z);
    const VolumeFields thick = fields_at(spacing);
    for (std::size_t i = 0; i < cubic.features.size(); ++i)
      ASSERT_NEAR(thick.features[i].weight, cubic.features[i].weight, 1e-5f) << i;
    // No reach: the feature test is then whether the cell has a corner of θ2 above it.
    const SurfaceCells cubic_cells = find_surface_cells(cubic, feature, 0.0f);
    const SurfaceCells thick_cells = find_surface_cells(thick, feature, 0.0f);
    int passed = 0;
    for (int k = 0; k < 500; ++k) {
      const vec3 g = vec3(along(rng), along(rng), along(rng)) * vec3(o.dims - 1);
      const bool in_cubic = passes_feature_test(cubic.view(), cubic_cells.view(), feature, g, 1.0f);
      EXPECT_EQ(passes_feature_test(thick.view(), thick_cells.view(), feature, g * spacing, 1.0f), in_cubic) << k;
      passed += in_cubic;
    }
    EXPECT_GT(passed, 50);  // both answers are tested
    EXPECT_LT(passed, 450);
  }
}

// A float distance-field sphere of radius 11 about (20, 20, 20) in 40³ voxels, its θ1
// weights for the iso-value 0 with k = 1 voxel (|∇f| = 1), and 300 points within 1.5
// voxels of it.
struct CleanSphere {
  vec3 center{20.0f};
  float radius = 11.0f;
  Field field = test::sphere_distance(center, radius);
  FeatureParams feature;
  VolumeFields fields;
  std::vector<vec3> points = points_near_sphere(center, radius, 1.5f, 300, 5);

  CleanSphere() {
    test::SampleVolumeOptions o;
    o.dims = ivec3(40);
    fields = compute_fields(test::sample_volume(field, o));
    feature.smoothing = 1;
    set_feature(fields, feature);
  }
};

TEST(VolumeProjection, PredictorAndCorrectorLandOnAFloatSphere) {
  const CleanSphere sphere;
  for (VolumeMethod m : {VolumeMethod::predictor, VolumeMethod::predictor_corrector}) {
    const VolumeParams params = VolumeParams::from_voxels(1.0f, m);
    const Errors e = project_all(sphere.fields, sphere.feature, params, sphere.field, sphere.points);
    std::printf("method %d: rms %.4f max %.4f normal %.3f deg failed %d\n", int(m), e.rms_distance, e.max_distance,
                e.max_normal_deg, e.failed);
    // The lattice noise bound of the test above; normals to its slope over the disc,
    // 0.13/3 rad ≈ 2.5°, doubled at the disc's rim where γ may land.
    EXPECT_EQ(e.failed, 0);
    EXPECT_LT(e.rms_distance, 0.07f);
    EXPECT_LT(e.max_distance, 0.15f);
    EXPECT_LT(e.max_normal_deg, 5.0f);
  }
}

// The corrector (Eq. 4) must do its job: on a clean float sphere its MLS-like weights Θ
// (θ3 centred on the point being projected) remove most of the predictor's lattice bias,
// 0.020 against 0.030 voxels rms (docs/paper-notes.md, §4): it moves every point it is
// given, and lands markedly closer. A corrector that returned P(r) unchanged, or one no
// better than the predictor, fails here.
TEST(VolumeProjection, CorrectorImprovesTheCleanSphere) {
  const CleanSphere s;
  const VolumeParams predictor = VolumeParams::from_voxels(1.0f, VolumeMethod::predictor);
  const VolumeParams corrector = VolumeParams::from_voxels(1.0f, VolumeMethod::predictor_corrector);
  const Errors predicted = project_all(s.fields, s.feature, predictor, s.field, s.points);
  const Errors corrected = project_all(s.fields, s.feature, corrector, s.field, s.points);
  EXPECT_LT(corrected.rms_distance, 0.8f * predicted.rms_distance);
  VoxelNeighbourhood nb;
  int moved = 0;
  for (const vec3& r : s.points) {
    const VolumeProjection p = project_volume_point(s.fields.view(), corrector, r, nb);
    moved += glm::length(p.point - p.predicted) > 1e-3f;
  }
  EXPECT_GT(moved, int(s.points.size()) * 9 / 10);
}

// What the GPU runs (VoxelScratch there): N(x) walked on the lattice at each pass instead of
// stored. The same voxels with the same weights, so the same projections up to the rounding
// of sums taken in another order (the stored ones run in SIMD lanes), with both methods, from
// up to 2.5 voxels off the surface, where the predictor moves the point that far.
TEST(VolumeProjection, WalkedNeighbourhoodsProjectAsStoredOnes) {
  const CleanSphere s;
  std::vector<vec3> points = s.points;
  for (const vec3& p : points_near_sphere(s.center, s.radius, 2.5f, 300, 11)) points.push_back(p);
  for (VolumeMethod m : {VolumeMethod::predictor, VolumeMethod::predictor_corrector}) {
    const VolumeParams params = VolumeParams::from_voxels(1.0f, m);
    VoxelNeighbourhood stored;
    WalkedVoxelNeighbourhood walked;
    int ok = 0;
    for (const vec3& r : points) {
      const VolumeProjection a = project_volume_point(s.fields.view(), params, r, stored);
      const VolumeProjection b = project_volume_point(s.fields.view(), params, r, walked);
      ASSERT_EQ(a.status, b.status) << r.x << " " << r.y << " " << r.z;
      ok += a.status == VolumeProjectionStatus::ok;
      EXPECT_LT(glm::length(a.point - b.point), 1e-4f);
      EXPECT_LT(glm::length(a.predicted - b.predicted), 1e-4f);
      EXPECT_GT(glm::dot(a.normal, b.normal), 1 - 1e-6f);
    }
    EXPECT_GT(ok, int(points.size()) * 9 / 10);
  }
}

void expect_same(const VolumeProjection& a, const VolumeProjection& b) {
  EXPECT_EQ(a.status, b.status);
  EXPECT_EQ(a.stopped_early, b.stopped_early);
  EXPECT_EQ(a.predicted, b.predicted);
  EXPECT_EQ(a.point, b.point);
  EXPECT_EQ(a.normal, b.normal);
  EXPECT_EQ(a.frame.origin, b.frame.origin);
  EXPECT_EQ(a.polynomial.a, b.polynomial.a);
  EXPECT_EQ(a.polynomial.b, b.polynomial.b);
  EXPECT_EQ(a.polynomial.c, b.polynomial.c);
  EXPECT_EQ(a.polynomial.d, b.polynomial.d);
}

// The marcher's shortcut (marcher.hpp): given a reach, the predictor stops early once it has
// moved the point beyond it, and says so; resumed, it ends where one uninterrupted run ends,
// with the same iteration cap; and a projection that stays within the reach is the full one.
// Points 1.5 voxels off the sphere move farther than the reaches, those on it do not.
TEST(VolumeProjection, PredictorStopsOnlyBeyondItsReachAndResumes) {
  const CleanSphere s;
  const FieldView fields = s.fields.view();
  VoxelNeighbourhood nb;
  for (int cap : {1, 2, 3, 8})
    for (float reach : {0.4f, 0.8f}) {
      VolumeParams params = VolumeParams::from_voxels(1.0f, VolumeMethod::predictor);
      params.max_predictor_iterations = cap;
      int far_stopped = 0, near_stopped = 0;
      for (const vec3& p : s.points) {
        const vec3 out = s.center + (s.radius + 1.5f) * glm::normalize(p - s.center);
        const VolumeProjection full = predict(fields, params, out, nb);
        EXPECT_FALSE(full.stopped_early);
        if (cap == 8) EXPECT_LT(s.field.distance(full.point), 0.15f);
        Predictor<VoxelNeighbourhood> predictor(fields, out);
        const VolumeProjection early = predictor.run(params, nb, reach);
        far_stopped += early.stopped_early;
        if (early.stopped_early) EXPECT_GT(glm::length(early.frame.origin - out), reach);
        expect_same(predictor.run(params, nb), full);

        const vec3 on = s.center + s.radius * glm::normalize(p - s.center);
        const VolumeProjection near = Predictor<VoxelNeighbourhood>(fields, on).run(params, nb, reach);
        near_stopped += near.stopped_early;
        expect_same(near, predict(fields, params, on, nb));
      }
      // With one iteration allowed there is nothing to stop early.
      EXPECT_EQ(far_stopped, cap == 1 ? 0 : int(s.points.size())) << cap << " " << reach;
      EXPECT_EQ(near_stopped, 0) << cap << " " << reach;
    }
}

}  // namespace pss
