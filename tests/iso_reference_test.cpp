// The real-data reference (support/iso_reference.hpp) checked on analytic volumes before it
// judges pss on scans: its hits lie on the sampled sphere, its silhouette is the analytic
// one but for the rim, box faces are never surfaces, its mesh distances equal brute force.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "pss/render/camera.hpp"
#include "pss/render/rendered_frame.hpp"
#include "pss/volume/render_volume.hpp"
#include "support/iso_reference.hpp"
#include "support/volumes.hpp"

namespace pss {
namespace {

constexpr float kRadius = 14.5f;
const vec3 kCenter(23.3f, 24.1f, 23.7f);

Volume sphere_volume() {
  test::SampleVolumeOptions o;
  o.dims = ivec3(48);
  return test::sample_volume(test::sphere_distance(kCenter, kRadius), o);
}

// Distance from the sphere's centre to the ray's line, for rays in front of the centre.
float ray_center_distance(const Ray& r) {
  const vec3 oc = kCenter - r.origin;
  return glm::length(oc - glm::dot(oc, r.dir) * r.dir);
}

TEST(IsoReference, HitsLieOnTheSampledSphereAndTheSilhouetteIsAnalyticButForTheRim) {
  const Volume volume = sphere_volume();
  for (const vec2 view : {vec2(0, 0), vec2(37, 21), vec2(200, -60)}) {
    const Camera camera = test::volume_camera(volume.view().bounds(), 160, 120, view.x, view.y);
    const test::ReferenceImage ref = test::cast_iso_reference(volume.view(), 0.0f, camera);
    std::int64_t hits = 0, disagree = 0;
    float worst = 0, worst_angle = 0;
    for (int y = 0; y < camera.height; ++y)
      for (int x = 0; x < camera.width; ++x) {
        const test::ReferencePixel& p = ref.pixels[std::size_t(y * camera.width + x)];
        const Ray ray = camera.primary_ray(x, y);
        const float miss = ray_center_distance(ray) - kRadius;  // > 0: the analytic ray misses
        if (p.found) {
          ++hits;
          worst = std::max(worst, std::abs(glm::length(p.point - kCenter) - kRadius));
          const float cos = glm::dot(p.normal, glm::normalize(p.point - kCenter));
          worst_angle = std::max(worst_angle, std::acos(std::min(1.0f, cos)) * 57.29578f);
          EXPECT_NEAR(p.t, glm::length(p.point - ray.origin), 1e-3f * p.t);
        }
        if (p.found != (miss < 0)) {
          ++disagree;
          // Only on the rim, where the trilinear sphere and the true one part by less than
          // the interpolation error (≪ 0.1 voxel) across the ray.
          EXPECT_LT(std::abs(miss), 0.1f) << "pixel " << x << "," << y;
        }
      }
    EXPECT_GT(hits, 1000);  // the framing fits the box's bounding sphere, radius 40.7
    EXPECT_LT(worst, 0.05f) << "view " << view.x << "," << view.y;
    // Central differences of a distance field are within a few degrees of its normal.
    EXPECT_LT(worst_angle, 3.0f);
    EXPECT_LT(disagree, hits / 100);
  }
}

TEST(IsoReference, BoxFacesAreNotSurfaces) {
  // f = x: the ray from +x enters through a face above iso, the ray from −x below; both
  // must find only the plane x = 20.4, never the face they enter through.
  test::Field plane{[](vec3 p) { return p.x; }, [](vec3) { return vec3(1, 0, 0); }, 20.4f};
  test::SampleVolumeOptions o;
  o.dims = ivec3(40, 32, 36);
  const Volume volume = test::sample_volume(plane, o);
  for (const float azimuth : {90.0f, -90.0f, 60.0f, -120.0f}) {
    const Camera camera = test::volume_camera(volume.view().bounds(), 96, 96, azimuth, 15);
    const test::ReferenceImage ref = test::cast_iso_reference(volume.view(), 20.4f, camera);
    std::int64_t hits = 0;
    for (const test::ReferencePixel& p : ref.pixels)
      if (p.found) {
        ++hits;
        EXPECT_NEAR(p.point.x, 20.4f, 1e-3f);
        EXPECT_NEAR(std::abs(p.normal.x), 1.0f, 1e-4f);
      }
    EXPECT_GT(hits, 1000) << "azimuth " << azimuth;
  }
  // A volume above iso everywhere has no surface at all, not even its box.
  Volume full = volume;
  std::fill(full.values.begin(), full.values.end(), 100.0f);
  const Camera camera = test::volume_camera(full.view().bounds(), 64, 64, 30, 10);
  for (const test::ReferencePixel& p : test::cast_iso_reference(full.view(), 50.0f, camera).pixels)
    EXPECT_FALSE(p.found);
  EXPECT_TRUE(test::ReferenceMesh(full.view(), 50.0f).triangles().empty());
}

TEST(IsoReference, PointTriangleDistanceIsTheMinimumOverTheTriangle) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-1, 1);
  const auto random_vec = [&] { return vec3(u(rng), u(rng), u(rng)); };
  for (int n = 0; n < 200; ++n) {
    const test::Triangle t{random_vec(), random_vec(), random_vec()};
    const vec3 p = 1.5f * random_vec();
    // Dense barycentric sampling bounds the exact distance from above, within its spacing.
    float sampled = kInfinity;
    constexpr int kSteps = 200;
    for (int i = 0; i <= kSteps; ++i)
      for (int j = 0; i + j <= kSteps; ++j) {
        const float a = float(i) / kSteps, b = float(j) / kSteps;
        sampled = std::min(sampled, glm::length(p - (t.a + a * (t.b - t.a) + b * (t.c - t.a))));
      }
    const float exact = test::point_triangle_distance(p, t);
    const float spacing = 2.0f * std::max({glm::length(t.b - t.a), glm::length(t.c - t.a), 1e-3f}) / kSteps;
    EXPECT_LE(exact, sampled + 1e-5f);
    EXPECT_GE(exact, sampled - spacing);
  }
  // A degenerate triangle is its edges.
  const test::Triangle flat{vec3(0, 0, 0), vec3(1, 0, 0), vec3(2, 0, 0)};
  EXPECT_NEAR(test::point_triangle_distance(vec3(3, 1, 0), flat), std::sqrt(2.0f), 1e-6f);
}

TEST(IsoReference, MeshDistanceThroughTheGridEqualsBruteForce) {
  // A noisy volume makes a mesh with many small, thin and degenerate triangles.
  test::SampleVolumeOptions o;
  o.dims = ivec3(32, 28, 30);
  o.noise = 0.3f;
  const Volume volume = test::sample_volume(test::sphere_distance(vec3(15.2f, 13.9f, 14.6f), 9.0f), o);
  const test::ReferenceMesh mesh(volume.view(), 0.0f);
  ASSERT_GT(mesh.triangles().size(), 1000u);
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(-20, 50);
  for (int n = 0; n < 1000; ++n) {
    // Inside the box, near it, and far outside.
    const vec3 p = n < 900 ? vec3(u(rng), u(rng), u(rng)) : vec3(u(rng), u(rng), u(rng)) * 20.0f;
    const float brute = mesh.distance_brute_force(p);
    EXPECT_NEAR(mesh.distance(p), brute, 1e-5f * std::max(1.0f, brute)) << p.x << "," << p.y << "," << p.z;
  }
  EXPECT_EQ(test::ReferenceMesh().distance(vec3(0.0f)), kInfinity);
}

TEST(IsoReference, MeshLiesOnTheSampledSphereAndAgreesWithTheRays) {
  const Volume volume = sphere_volume();
  const test::ReferenceMesh mesh(volume.view(), 0.0f);
  for (const test::Triangle& t : mesh.triangles())
    for (const vec3 p : {t.a, t.b, t.c}) EXPECT_LT(std::abs(glm::length(p - kCenter) - kRadius), 0.05f);
  // The reference's own hits, scored as if pss had made them: no holes, no phantom,
  // within the interpolation error of the mesh, normals identical.
  const Camera camera = test::volume_camera(volume.view().bounds(), 128, 128, 30, 10);
  const test::ReferenceImage ref = test::cast_iso_reference(volume.view(), 0.0f, camera);
  std::vector<Hit> hits(ref.pixels.size());
  for (std::size_t i = 0; i < hits.size(); ++i)
    if (ref.pixels[i].found) {
      hits[i].flags = kHitFound;
      hits[i].point = ref.pixels[i].point;
      hits[i].normal = -ref.pixels[i].normal;  // either orientation counts
    }
  test::ReferenceComparison c = test::compare_to_reference(hits, ref, mesh, 1.0f);
  EXPECT_EQ(c.hole_pixels, 0);
  EXPECT_EQ(c.phantom_pixels, 0);
  EXPECT_LT(c.p99_distance, 0.05);
  EXPECT_LT(c.mean_normal_angle_deg, 0.01);
  EXPECT_NEAR(c.mean_depth_difference, 0.0, 1e-6);
  // One hit where the reference has none is phantom; one dropped is a hole.
  std::size_t miss = 0, hit = 0;
  while (ref.pixels[miss].found) ++miss;
  while (!ref.pixels[hit].found) ++hit;
  hits[miss].flags = kHitFound;
  hits[miss].point = kCenter + vec3(0, 0, kRadius + 3);
  hits[hit].flags = 0;
  c = test::compare_to_reference(hits, ref, mesh, 1.0f);
  EXPECT_EQ(c.phantom_pixels, 1);
  EXPECT_EQ(c.hole_pixels, 1);
  EXPECT_NEAR(c.max_distance, 3.0, 0.05);
  EXPECT_DOUBLE_EQ(c.holes, 1.0 / double(c.object_pixels));
}

TEST(IsoReference, MeasuresPssThroughTheSamePixels) {
  // The plumbing of measure_against_reference on a clean analytic sphere: pss's pixel
  // (x, y) is the reference's, so the two hit points nearly coincide wherever both hit.
  const Volume volume = sphere_volume();
  const PreparedVolume prepared = test::prepare_iso(volume, 0.0f);
  const Camera camera = test::volume_camera(volume.view().bounds(), 96, 96, 30, 10);
  const test::ReferenceMesh mesh(volume.view(), 0.0f);
  const test::ReferenceMeasurement m = test::measure_against_reference(prepared, 0.0f, camera, mesh);
  EXPECT_GT(m.comparison.object_pixels, 700);
  EXPECT_LT(m.comparison.mean_depth_difference, 0.25);
  EXPECT_LT(m.comparison.holes, 0.02);
  EXPECT_LT(m.comparison.phantom, 0.02);
}

}  // namespace
}  // namespace pss
