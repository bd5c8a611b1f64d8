// The facing vote that turns each oriented part (points/facing_vote.hpp), against the
// divergence theorem's sign on shapes whose outside is known.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "pss/points/facing_vote.hpp"
#include "pss/points/orient_normals.hpp"
#include "pss/points/project_cloud.hpp"
#include "support/shapes.hpp"

namespace pss {
namespace {

float inverse_area(float rho) { return 1.0f / (rho * rho); }

// A unit sphere sampled eight times as densely below its equator as above, each sample's ρ
// growing with its spacing: weighed by the areas the samples cover, the outward normals vote
// outward; counted alone, the dense lower half's downward normals would outvote them.
TEST(FacingVote, ASphereEightTimesDenserBelowVotesOutward) {
  std::mt19937 rng(5);
  std::normal_distribution<float> g(0.0f, 1.0f);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  FacingVote outward, inward;
  int kept = 0;
  while (kept < 9000) {
    const vec3 p = glm::normalize(vec3(g(rng), g(rng), g(rng)));
    const bool upper = p.z > 0;
    if (upper && u(rng) > 1.0f / 8) continue;
    const float rho = upper ? 0.05f * std::sqrt(8.0f) : 0.05f;
    outward.add(p, p, inverse_area(rho), ProjectionStatus::converged);
    inward.add(p, -p, inverse_area(rho), ProjectionStatus::converged);
    ++kept;
  }
  EXPECT_EQ(outward.sign(), 1);
  EXPECT_EQ(inward.sign(), -1);
}

// Open surfaces: the ground faces up by its normals even where it is exactly level; a wall
// has no say, nor normals that do not agree; a point that did not converge has none either,
// however many there are.
TEST(FacingVote, OpenSurfacesAndUnconvergedPoints) {
  FacingVote level, wall, strays;
  for (int i = 0; i < 100; ++i) {
    const float x = float(i % 10) * 0.1f, y = float(i / 10) * 0.1f;
    // ρ = 1/8, z = 1/4: every product exact, so that only δ below the lowest point speaks
    level.add(vec3(x, y, 0.25f), vec3(0, 0, 1), inverse_area(0.125f), ProjectionStatus::converged);
    wall.add(vec3(x, 0.5f, y), vec3(0, 1, 0), inverse_area(0.1f), ProjectionStatus::converged);
    strays.add(vec3(x, y, 0.25f), vec3(0, 0, 1), inverse_area(0.1f), ProjectionStatus::converged);
  }
  for (int i = 0; i < 1000; ++i)
    strays.add(vec3(0.5f, 0.5f, 0.9f), vec3(0, 0, -1), inverse_area(0.1f), ProjectionStatus::not_converged);
  EXPECT_EQ(level.sign(), 1);
  EXPECT_EQ(wall.sign(), 0);
  // Normals of either sign at random (a part of a tree crown): under a quarter agree, no say.
  FacingVote crown;
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  for (int i = 0; i < 400; ++i) {
    const vec3 n = glm::normalize(vec3(u(rng), u(rng), u(rng)) + vec3(0, 0, 0.02f));
    crown.add(vec3(u(rng), u(rng), u(rng)), n, inverse_area(0.1f), ProjectionStatus::converged);
  }
  EXPECT_EQ(crown.sign(), 0);
  EXPECT_EQ(strays.sign(), 1);
  EXPECT_EQ(FacingVote().sign(), 0);
}

// Pieces add with their turns: a sphere's lower half facing out, which alone votes inward
// (it faces down everywhere), and its upper half, held turned, vote outward together once
// the upper half is added turned back.
TEST(FacingVote, PiecesAddWithTheirTurns) {
  FacingVote lower, upper_turned;
  for (int i = 0; i < 2000; ++i) {
    const float z = 1 - 2 * (float(i) + 0.5f) / 2000, r = std::sqrt(1 - z * z), a = float(i) * 2.39996323f;
    const vec3 p(r * std::cos(a), r * std::sin(a), z);
    if (z < 0) lower.add(p, p, inverse_area(0.05f), ProjectionStatus::converged);
    else upper_turned.add(p, -p, inverse_area(0.05f), ProjectionStatus::converged);
  }
  EXPECT_EQ(lower.sign(), -1);
  FacingVote whole = lower;
  whole.add(upper_turned, true);
  EXPECT_EQ(whole.sign(), 1);
  FacingVote turned_whole = upper_turned;
  turned_whole.add(lower, true);
  EXPECT_EQ(turned_whole.sign(), -1);
}

// A noisy sphere with a fifth as many strays about it (test::noisy_sphere_with_strays): the
// strays above its top seeded the tree, and their normals, fitted to other strays or not at
// all, turned every normal of the sphere inward with these seeds. The vote turns it out.
TEST(OrientNormals, StraysAboveASphereDoNotTurnItInward) {
  for (const auto& [strays, seed] : {std::pair<std::size_t, unsigned>{600, 7}, {2400, 9}}) {
    PointCloud cloud;
    cloud.positions = test::noisy_sphere_with_strays(strays, 5, seed);
    ProjectionParams params = ProjectionParams::from_h(test::suggested_h(cloud));
    params.support = Support::adaptive;
    Stats stats;
    const CloudProjection out = project_cloud(cloud, params, Backend::cpu, stats);
    std::size_t on = 0, outward = 0;
    for (std::size_t i = 0; i < cloud.size(); ++i) {
      const vec3 p = out.cloud.positions[i];
      if (std::abs(glm::length(p) - 1) > 0.05f || out.status[i] != ProjectionStatus::converged) continue;
      ++on;
      outward += glm::dot(p, out.cloud.normals[i]) > 0;
    }
    EXPECT_GT(on, 11000u) << seed;
    EXPECT_EQ(outward, on) << seed;
  }
}

}  // namespace
}  // namespace pss
