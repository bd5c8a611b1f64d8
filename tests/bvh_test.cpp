// The BVH over balls against brute force: the same nearest ball entry for random rays,
// from outside and inside the cloud, axis-parallel ones included, and with a t_min.
#include <gtest/gtest.h>

#include <random>

#include "pss/spatial/bvh.hpp"

namespace pss {
namespace {

float brute_force_entry(const std::vector<vec3>& centers, float radius, const Ray& ray, float t_min, int& which) {
  float best = kInfinity;
  which = -1;
  for (std::size_t i = 0; i < centers.size(); ++i) {
    float t0, t1;
    if (!ray_ball(ray, centers[i], radius, t0, t1)) continue;
    const float t = t0 > t_min ? t0 : (t1 > t_min ? t_min : kInfinity);  // entry, or t_min when inside
    if (t < best) {
      best = t;
      which = int(i);
    }
  }
  return best;
}

float bvh_entry(const Bvh& bvh, const std::vector<vec3>& centers, float radius, const Ray& ray, float t_min,
                int& which) {
  const BvhView view = bvh.view();
  float best = kInfinity;
  which = -1;
  view.closest(ray, t_min, best, [&](int k, float& t_best) {
    const int i = view.primitives[k];
    float t0, t1;
    if (!ray_ball(ray, centers[i], radius, t0, t1)) return;
    const float t = t0 > t_min ? t0 : (t1 > t_min ? t_min : kInfinity);
    if (t < t_best) {
      t_best = t;
      which = i;
    }
  });
  return best;
}

std::vector<vec3> random_centers(std::size_t n, std::mt19937& rng) {
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  std::vector<vec3> c(n);
  for (vec3& p : c) p = vec3(u(rng), u(rng), 0.3f * u(rng));
  return c;
}

TEST(Bvh, NearestBallMatchesBruteForce) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  std::normal_distribution<float> g(0.0f, 1.0f);
  const float radius = 0.03f;
  const std::vector<vec3> centers = random_centers(3000, rng);
  const Bvh bvh(centers, radius);
  EXPECT_LE(bvh.depth(), 8);  // 4-wide: log4(3000 / 4) ≈ 5 levels, and uneven SAH splits
  int hits = 0;
  for (int i = 0; i < 4000; ++i) {
    Ray ray;
    // Half from outside toward the slab, half from inside it in any direction; some
    // exactly along an axis (infinite inverse components).
    ray.origin = i % 2 ? vec3(2 * u(rng), 2 * u(rng), 2.0f) : vec3(u(rng), u(rng), 0.3f * u(rng));
    ray.dir = i % 7 == 0 ? vec3(0, 0, -1) : glm::normalize(vec3(g(rng), g(rng), g(rng) - (i % 2 ? 2.0f : 0.0f)));
    const float t_min = i % 3 == 0 ? 0.1f : 0.0f;
    int a, b;
    const float expected = brute_force_entry(centers, radius, ray, t_min, a);
    const float got = bvh_entry(bvh, centers, radius, ray, t_min, b);
    ASSERT_EQ(expected, got) << "ray " << i;
    if (a >= 0) ++hits;
  }
  EXPECT_GT(hits, 1000);  // the test exercises hits, not only misses
}

// Children are visited near first, so the first hit prunes what lies behind it: a ray along
// a row of 2,000 overlapping balls tests the leaf of the first, where visiting far first
// tests all of them. The count of leaf calls, not time, so the test is exact.
TEST(Bvh, NearestChildrenFirstPruneTheRest) {
  std::vector<vec3> centers;
  for (int i = 0; i < 2000; ++i) centers.push_back(vec3(float(i), 0.0f, 0.0f));
  const Bvh bvh(centers, 0.6f);
  for (const float sign : {1.0f, -1.0f}) {
    const Ray ray{vec3(sign > 0 ? -5.0f : 2004.0f, 0.01f, 0.0f), vec3(sign, 0.0f, 0.0f)};
    int calls = 0, which = -1;
    float best = kInfinity;
    const BvhView view = bvh.view();
    view.closest(ray, 0.0f, best, [&](int k, float& t_best) {
      ++calls;
      float t0, t1;
      if (ray_ball(ray, centers[view.primitives[k]], 0.6f, t0, t1) && t0 < t_best) {
        t_best = t0;
        which = view.primitives[k];
      }
    });
    EXPECT_EQ(which, sign > 0 ? 0 : 1999);
    // One leaf, the first ball's (4 primitives a leaf by default): a far slot pushed before
    // the hit was found is dropped when popped, and a near one is visited first.
    EXPECT_LE(calls, 4) << "from the " << (sign > 0 ? "start" : "end");
  }
}

TEST(Bvh, EmptyAndSinglePrimitiveAndCoincidentCentres) {
  const Bvh empty({}, 1.0f);
  int which;
  const Ray down{vec3(0, 0, 5), vec3(0, 0, -1)};
  EXPECT_EQ(bvh_entry(empty, {}, 1.0f, down, 0.0f, which), kInfinity);

  const std::vector<vec3> one{vec3(0.0f)};
  EXPECT_FLOAT_EQ(bvh_entry(Bvh(one, 1.0f), one, 1.0f, down, 0.0f, which), 4.0f);

  // All centres equal: no split is possible, one leaf holds them all.
  const std::vector<vec3> same(50, vec3(0.0f));
  const Bvh bvh(same, 1.0f);
  EXPECT_EQ(bvh.nodes().size(), 1u);
  EXPECT_FLOAT_EQ(bvh_entry(bvh, same, 1.0f, down, 0.0f, which), 4.0f);
}

TEST(Bvh, RejectsInvalidRadius) {
  const std::vector<vec3> one{vec3(0.0f)};
  EXPECT_ANY_THROW(Bvh(one, 0.0f));
  EXPECT_ANY_THROW(Bvh(one, NAN));
}

}  // namespace
}  // namespace pss
