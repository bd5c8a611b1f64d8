// The spacing estimate and the default h against a square lattice, where the distances to
// the nearest samples are known: s (4 of them), √2·s (4), 2s (4), √5·s (8), …
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "pss/core/error.hpp"
#include "pss/points/spacing.hpp"

namespace pss {
namespace {

std::vector<vec3> lattice(int n, float s) {
  std::vector<vec3> p;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) p.push_back(vec3(float(i) * s, float(j) * s, 0.0f));
  return p;
}

TEST(Spacing, SquareLatticeDistancesAreKnown) {
  const float s = 0.01f;
  const SpacingEstimate e = estimate_spacing(lattice(60, s));
  EXPECT_NEAR(e.mean_nearest, s, 1e-6);
  // The 15th nearest: after 4 + 4 + 4 closer ones, among the 8 at √5·s (the median point lies
  // deep inside the lattice, where no neighbour is cut off).
  EXPECT_EQ(e.k, 15);
  EXPECT_NEAR(e.median_kth, std::sqrt(5.0) * s, 1e-6);
  EXPECT_NEAR(e.suggested_h, e.median_kth, 1e-9);
  EXPECT_FLOAT_EQ(default_h(lattice(60, s)), float(e.suggested_h));
}

// The spread of the k-th neighbour's distance, against brute force: a lattice of spacing s
// beside one 8 times sparser, jittered so that no two distances tie. The least lies inside
// the dense part, the largest at a corner of the sparse one.
TEST(Spacing, SpreadOfTheKthNeighbourMatchesBruteForce) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> jitter(-0.1f, 0.1f);
  std::vector<vec3> points = lattice(20, 1.0f);
  for (const vec3& p : lattice(10, 8.0f)) points.push_back(p + vec3(40.0f, 0.0f, 0.0f));
  for (vec3& p : points) p += vec3(jitter(rng), jitter(rng), jitter(rng));
  std::vector<double> kth;
  for (const vec3& p : points) {
    std::vector<double> d;
    for (const vec3& q : points) d.push_back(glm::length(glm::dvec3(p) - glm::dvec3(q)));
    std::nth_element(d.begin(), d.begin() + 15, d.end());  // d[0] is the point itself
    kth.push_back(d[15]);
  }
  const SpacingEstimate e = estimate_spacing(points);
  EXPECT_NEAR(e.min_kth, *std::min_element(kth.begin(), kth.end()), 1e-5);
  EXPECT_NEAR(e.max_kth, *std::max_element(kth.begin(), kth.end()), 1e-5);
  EXPECT_GT(e.max_kth / e.min_kth, 8.0);
  std::nth_element(kth.begin(), kth.begin() + kth.size() / 2, kth.end());
  EXPECT_NEAR(e.median_kth, kth[kth.size() / 2], 1e-5);
}

TEST(Spacing, DefaultHOfFewerThanTwoSamplesIsOne) {
  EXPECT_EQ(default_h(std::vector<vec3>{}), 1.0f);
  EXPECT_EQ(default_h(std::vector<vec3>{vec3(3.0f)}), 1.0f);
  EXPECT_THROW(estimate_spacing(std::vector<vec3>{vec3(3.0f)}), Error);
  EXPECT_GT(default_h(std::vector<vec3>{vec3(0.0f), vec3(1.0f, 0.0f, 0.0f)}), 0.0f);
}

}  // namespace
}  // namespace pss
