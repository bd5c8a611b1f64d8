// The ray/PSS intersection's parts against brute force and analytic truth: nearest_local_hit
// (BVH, ball and slab clipping) against a loop over every local polynomial in its ball, and
// intersect_pss's hits against a sphere's first crossing and an open patch's extent.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "pss/points/render_cloud.hpp"
#include "support/shapes.hpp"

namespace pss {
namespace {

// The nearest root, inside its ball, of every local polynomial: no BVH, no slab.
LocalHit brute_force_local_hit(const PointSurfaceView& s, std::span<const LocalPolynomial> locals, const Ray& ray) {
  LocalHit best;
  const float b = s.params.ball_radius;
  for (std::size_t k = 0; k < locals.size(); ++k) {
    const LocalPolynomial& lp = locals[k];
    float t0, t1;
    if (!ray_ball(ray, lp.origin, b, t0, t1)) continue;
    const float lo = t0 > 0 ? t0 : 0;
    if (!(lo < t1)) continue;
    const Frame frame = lp.frame();
    float roots[2];
    const int n = intersect_graph(lp.g, frame.to_local(ray.at(lo)), frame.direction_to_local(ray.dir), roots);
    for (int i = 0; i < n; ++i) {
      const float t = lo + roots[i];
      if (t > 0 && t >= lo && t <= t1 && t < best.t) {
        best.t = t;
        best.local = int(k);
      }
    }
  }
  return best;
}

// A noisy torus: curved, uneven polynomials, slabs of every height.
PointCloud noisy_torus(std::size_t count) {
  test::SampleOptions o;
  o.count = count;
  o.noise = 0.01f;
  return test::sample(test::Torus{}, o);
}

// A ray from a sphere of radius 3 toward a point near the torus: many of them grazing.
Ray ray_toward_torus(std::mt19937& rng) {
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  const vec3 from = 3.0f * glm::normalize(vec3(u(rng), u(rng), u(rng)));
  const vec3 to(1.3f * u(rng), 1.3f * u(rng), 0.4f * u(rng));
  return Ray{from, glm::normalize(to - from)};
}

TEST(RayPss, NearestLocalHitIsTheNearestOfAllLocalPolynomials) {
  const PointCloud cloud = noisy_torus(3000);
  Stats stats;
  const PreparedCloud prepared(cloud, RayPssParams::from_h(test::suggested_h(cloud)), Backend::cpu, stats);
  const PointSurfaceView view = prepared.view();
  std::mt19937 rng(7);
  int hits = 0, grazing = 0;
  for (int i = 0; i < 4000; ++i) {
    const Ray ray = ray_toward_torus(rng);
    const LocalHit fast = nearest_local_hit(view, ray, 0.0f, kInfinity);
    const LocalHit slow = brute_force_local_hit(view, prepared.locals(), ray);
    ASSERT_EQ(fast.local >= 0, slow.local >= 0) << i << ": " << fast.t << " vs " << slow.t;
    if (slow.local < 0) continue;
    ++hits;
    // The same root, found from the slab's entry rather than the ball's: equal up to float
    // rounding at coordinates of order b.
    EXPECT_NEAR(fast.t, slow.t, 1e-3f * view.params.ball_radius) << i;
    grazing += std::abs(glm::dot(ray.dir, view.locals[slow.local].normal)) < 0.2f;
  }
  EXPECT_GT(hits, 1000);
  EXPECT_GT(grazing, 50);
}

// (Not LocalHit: std::sort would find pss::swap beside std::swap.)
struct Crossing {
  float t;
  int local;
};

// Every crossing, inside its ball and beyond t_min, of every local polynomial, nearest first.
std::vector<Crossing> brute_force_crossings(std::span<const LocalPolynomial> locals, const Ray& ray, float t_min) {
  std::vector<Crossing> all;
  for (std::size_t k = 0; k < locals.size(); ++k) {
    const LocalPolynomial& lp = locals[k];
    float t0, t1;
    if (!ray_ball(ray, lp.origin, lp.radius, t0, t1)) continue;
    const float lo = std::max(t0, t_min);
    if (!(lo < t1)) continue;
    const Frame frame = lp.frame();
    float roots[2];
    const int n = intersect_graph(lp.g, frame.to_local(ray.at(lo)), frame.direction_to_local(ray.dir), roots);
    for (int i = 0; i < n; ++i)
      if (lo + roots[i] > t_min && roots[i] >= 0 && lo + roots[i] <= t1) all.push_back({lo + roots[i], int(k)});
  }
  std::sort(all.begin(), all.end(), [](const Crossing& a, const Crossing& b) { return a.t < b.t; });
  return all;
}

// The batches a ray's candidates come in (one BVH walk each), chained from each batch's last
// crossing, are the sequence of all its crossings in order, a second crossing of one
// polynomial included.
TEST(RayPss, BatchesOfLocalHitsAreEveryCrossingInOrder) {
  const PointCloud cloud = noisy_torus(3000);
  Stats stats;
  const PreparedCloud prepared(cloud, RayPssParams::from_h(test::suggested_h(cloud)), Backend::cpu, stats);
  const PointSurfaceView view = prepared.view();
  const float tolerance = 1e-3f * view.params.ball_radius;
  std::mt19937 rng(3);
  int long_sequences = 0, second_crossings = 0;
  for (int i = 0; i < 2000; ++i) {
    const Ray ray = ray_toward_torus(rng);
    const std::vector<Crossing> all = brute_force_crossings(prepared.locals(), ray, 0.0f);
    std::vector<Crossing> chained;
    float t_min = 0;
    for (int batches = 0; batches < 1000; ++batches) {
      const LocalHitBatch batch = nearest_local_hits(view, ray, t_min, kInfinity);
      ASSERT_LE(batch.count, LocalHitBatch::kSize);
      for (int j = 0; j < batch.count; ++j) chained.push_back({batch.t[j], batch.local[j]});
      if (batch.complete) break;
      ASSERT_EQ(batch.count, LocalHitBatch::kSize);
      t_min = batch.t[batch.count - 1];
    }
    ASSERT_EQ(chained.size(), all.size()) << i;
    for (std::size_t j = 0; j < all.size(); ++j) {
      EXPECT_NEAR(chained[j].t, all[j].t, tolerance) << i << ", crossing " << j;
      if (j > 0) EXPECT_GE(chained[j].t, chained[j - 1].t) << i;
    }
    long_sequences += all.size() > 2 * LocalHitBatch::kSize;
    for (std::size_t j = 1; j < all.size(); ++j)
      for (std::size_t k = 0; k < j; ++k) second_crossings += all[j].local == all[k].local;
  }
  EXPECT_GT(long_sequences, 200);
  EXPECT_GT(second_crossings, 20);
}

// intersect_pss against the paper's loop taken literally: one walk of the BVH per candidate,
// the next from the last one's crossing. The batches must try the same candidates in the same
// order, so every ray gets the same hit; grazing rays on a noisy torus and across an open
// patch's edges, many of them past their fourth candidate (a second batch and more).
TEST(RayPss, BatchesTryTheCandidatesOneWalkEachWould) {
  const PointCloud torus = noisy_torus(4000);
  test::SampleOptions o;
  o.count = 4000;
  o.noise = 0.005f;
  const PointCloud patch = test::sample_plane(1.0f, o);
  int past_first_batch = 0, hits = 0;
  for (const PointCloud* cloud : {&torus, &patch}) {
    Stats stats;
    const RayPssParams params = RayPssParams::from_h(test::suggested_h(*cloud));
    const PreparedCloud prepared(*cloud, params, Backend::cpu, stats);
    const PointSurfaceView view = prepared.view();
    std::mt19937 rng(13);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    for (int i = 0; i < 6000; ++i) {
      // Toward points near the shape from all around, nearly along its surface.
      const vec3 to(1.2f * u(rng), 1.2f * u(rng), 0.3f * u(rng));
      const vec3 dir = glm::normalize(vec3(u(rng), u(rng), 0.05f * u(rng)));
      const Ray ray{to - 3.0f * dir, dir};
      Hit expected;
      int candidates = 0;
      for (float t_from = 0; candidates < params.max_candidates; ++candidates) {
        const LocalHit c = nearest_local_hit(view, ray, t_from, kInfinity);
        if (c.local < 0 || candidate_hit(view, ray, c, 0.0f, kInfinity, params.max_iterations, expected)) break;
        t_from = c.t;
      }
      const Hit hit = intersect_pss(view, ray, 0.0f, kInfinity, params.max_iterations);
      ASSERT_EQ(hit.found(), expected.found()) << i << ", " << candidates << " candidates";
      if (!hit.found()) continue;
      ++hits;
      past_first_batch += candidates >= LocalHitBatch::kSize;
      EXPECT_EQ(hit.t, expected.t) << i;
      EXPECT_EQ(hit.iterations, expected.iterations) << i;
    }
  }
  EXPECT_GT(hits, 1500);
  EXPECT_GT(past_first_batch, 20);  // 47
}

// Where APSS's or RIMLS's fit has no surface (degenerate_normal: here every sample's normal
// zero, so RIMLS's gradient vanishes), the projection returns r itself; that is no hit,
// though r is within ε of it.
TEST(RayPss, AFitWithoutASurfaceIsNoHit) {
  test::SampleOptions o;
  o.count = 3000;
  const PointCloud cloud = test::sample(test::Sphere{}, o);
  for (const SurfaceOperator surface : {SurfaceOperator::apss, SurfaceOperator::rimls}) {
    RayPssParams params = RayPssParams::from_h(test::suggested_h(cloud));
    params.projection.surface = surface;
    Stats stats;
    const PreparedCloud prepared(cloud, params, Backend::cpu, stats);
    PointSurfaceView view = prepared.view();
    const Ray ray{vec3(0, 0, 3), vec3(0, 0, -1)};
    ASSERT_TRUE(intersect_pss(view, ray, 0.0f, kInfinity, params.max_iterations).found());
    const std::vector<vec3> zero(std::size_t(view.grid.count), vec3(0.0f));
    view.grid.normals = zero.data();
    const Projection p = project_onto_surface(view.grid, vec3(0, 0, 1.01f), params.projection, vec3(0, 0, 1), 0.0f);
    ASSERT_EQ(p.status, ProjectionStatus::degenerate_normal) << surface_name(surface);
    EXPECT_FALSE(intersect_pss(view, ray, 0.0f, kInfinity, params.max_iterations).found()) << surface_name(surface);
  }
}

// Every hit, a capped one (iterations spent, not converged) included, lies within b of the
// clean sphere, and is the ray's first crossing, also for the grazing rays near the
// silhouette, where the polynomials' intersections jump farthest. (Dropping the paper's
// "left the ball B(p_i, b)" rejection does not fail this test: on a smooth sphere the nearest
// root never leaves the ball. It matters at a patch's open edge: the next test, issue 9.)
TEST(RayPss, HitsAreTheFirstCrossingNearTheSilhouette) {
  test::SampleOptions o;
  o.count = 4000;
  const test::Sphere sphere;
  const PointCloud cloud = test::sample(sphere, o);
  Stats stats;
  const RayPssParams params = RayPssParams::from_h(test::suggested_h(cloud));
  const PreparedCloud prepared(cloud, params, Backend::cpu, stats);
  const PointSurfaceView view = prepared.view();
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f), radius(0.9f, 1.0f);
  int hits = 0, far = 0, capped = 0;
  float off_surface = 0;
  for (int i = 0; i < 20000; ++i) {
    const vec3 eye = 3.0f * glm::normalize(vec3(u(rng), u(rng), u(rng)));
    // Aim at a point of the silhouette's neighbourhood: across the view direction.
    const vec3 across = glm::normalize(glm::cross(eye, vec3(u(rng), u(rng), u(rng))));
    const Ray ray{eye, glm::normalize(radius(rng) * across - eye)};
    const Hit hit = intersect_pss(view, ray, 0.0f, kInfinity, params.max_iterations);
    if (!hit.found()) continue;
    off_surface = std::max(off_surface, std::abs(sphere.distance(hit.point)));
    capped += (hit.flags & kHitCapped) != 0;
    // The analytic crossings t1 ≤ t2 of the unit sphere.
    const float bq = glm::dot(ray.origin, ray.dir), c = glm::dot(ray.origin, ray.origin) - 1.0f;
    const float disc = bq * bq - c;
    if (disc <= 0) continue;  // the PSS's silhouette lies a little outside the sphere's
    const float t1 = -bq - std::sqrt(disc), t2 = -bq + std::sqrt(disc);
    ++hits;
    // Near tangency the two crossings merge: only a hit nearer the second one counts.
    far += std::abs(hit.t - t2) < std::abs(hit.t - t1) && t2 - t1 > 4 * params.ball_radius;
  }
  EXPECT_GT(hits, 5000);
  EXPECT_GT(capped, 50);
  EXPECT_LT(off_surface, params.ball_radius);
  EXPECT_EQ(far, 0) << "of " << hits;
}

// A noisy open patch, grazed by rays across its edges. The PSS ends within ρ of the samples
// (the projection needs neighbours within ρ), and the samples lie inside the square in x and
// y, so no hit may lie farther than ρ beyond the square's edge. Near the edge the
// projection's neighbourhood is one-sided and its polynomial tilts; a ray nearly parallel to
// it meets it far out, where there are no samples. Paper §5.2, "Intersection": if that point
// leaves the ball B(p_i, b) the candidate is rejected; without the rejection, with 1 to 3
// iterations, the step becomes a capped hit in empty space, 4 to 180 b beyond the edge.
// (With kAutoIterations the walk stops out there by itself: no neighbours.)
TEST(RayPss, GrazingRaysFindNoHitBeyondAnOpenPatch) {
  test::SampleOptions o;
  o.count = 4000;
  o.noise = 0.005f;  // ~h/14: enough for the fits at the edge to tilt
  const PointCloud cloud = test::sample_plane(1.0f, o);
  Stats stats;
  const RayPssParams params = RayPssParams::from_h(test::suggested_h(cloud));
  const PreparedCloud prepared(cloud, params, Backend::cpu, stats);
  const PointSurfaceView view = prepared.view();
  const float rho = params.projection.rho, b = params.ball_radius;
  for (const int cap : {1, 2, 3, kAutoIterations}) {
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f), elevation(0.02f, 0.22f), across(0.9f, 1.1f);
    int hits = 0, capped = 0, beyond = 0;
    float farthest = 0;
    for (int i = 0; i < 5000; ++i) {
      // Aim, from 1° to 13° above the plane and from any side, at a point within 0.1 of an edge.
      const float x = u(rng), y = u(rng);
      vec3 target(x, y, 0.0f);
      const float side = u(rng) < 0 ? -1.0f : 1.0f;
      (u(rng) < 0 ? target.x : target.y) = side * across(rng);
      const float e = elevation(rng), azimuth = 3.14159265f * u(rng);
      const vec3 dir(std::cos(e) * std::cos(azimuth), std::cos(e) * std::sin(azimuth), -std::sin(e));
      const Ray ray{target - 3.0f * dir, dir};
      const Hit hit = intersect_pss(view, ray, 0.0f, kInfinity, cap);
      if (!hit.found()) continue;
      ++hits;
      capped += (hit.flags & kHitCapped) != 0;
      const float dx = std::max(std::abs(hit.point.x) - 1.0f, 0.0f), dy = std::max(std::abs(hit.point.y) - 1.0f, 0.0f);
      const float out = std::sqrt(dx * dx + dy * dy);
      farthest = std::max(farthest, out);
      beyond += out > rho;
    }
    EXPECT_GT(hits, 2500) << "cap " << cap;
    if (cap <= 3) EXPECT_GT(capped, 200) << "cap " << cap;
    EXPECT_EQ(beyond, 0) << "cap " << cap << ": of " << hits << " hits, the farthest " << farthest / b
                         << " b beyond the edge (rho = " << rho / b << " b)";
  }
}

}  // namespace
}  // namespace pss
