// The ray/PSS intersection's parts against brute force: nearest_local_hit (BVH, ball and
// slab clipping) against a loop over every local polynomial in its ball.
#include <gtest/gtest.h>

#include <random>

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

TEST(RayPss, NearestLocalHitIsTheNearestOfAllLocalPolynomials) {
  test::SampleOptions o;
  o.count = 3000;
  o.noise = 0.01f;  // curved, uneven polynomials: slabs of every height
  const PointCloud cloud = test::sample(test::Torus{}, o);
  Stats stats;
  const PreparedCloud prepared(cloud, RayPssParams::from_h(test::suggested_h(cloud)), Backend::cpu, stats);
  const PointSurfaceView view = prepared.view();
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  int hits = 0, grazing = 0;
  for (int i = 0; i < 4000; ++i) {
    // Rays from a sphere of radius 3 toward points near the torus, many of them grazing.
    const vec3 from = 3.0f * glm::normalize(vec3(u(rng), u(rng), u(rng)));
    const vec3 to(1.3f * u(rng), 1.3f * u(rng), 0.4f * u(rng));
    const Ray ray{from, glm::normalize(to - from)};
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

}  // namespace
}  // namespace pss
