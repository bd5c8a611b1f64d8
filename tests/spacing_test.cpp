// The spacing estimate and the default h against a square lattice, where the distances to
// the nearest samples are known: s (4 of them), √2·s (4), 2s (4), √5·s (8), …
#include <gtest/gtest.h>

#include <cmath>
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

TEST(Spacing, DefaultHOfFewerThanTwoSamplesIsOne) {
  EXPECT_EQ(default_h(std::vector<vec3>{}), 1.0f);
  EXPECT_EQ(default_h(std::vector<vec3>{vec3(3.0f)}), 1.0f);
  EXPECT_THROW(estimate_spacing(std::vector<vec3>{vec3(3.0f)}), Error);
  EXPECT_GT(default_h(std::vector<vec3>{vec3(0.0f), vec3(1.0f, 0.0f, 0.0f)}), 0.0f);
}

}  // namespace
}  // namespace pss
