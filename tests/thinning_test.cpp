// Thinning the local polynomials (points/thinning.hpp) against its definition checked by
// brute force, on the two faces of a thin plate, and in the defaults of the renderer.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "pss/points/render_cloud.hpp"
#include "pss/points/thinning.hpp"
#include "support/shapes.hpp"

namespace pss {
namespace {

float off_graph(const LocalPolynomial& by, vec3 p) {
  const vec3 l = by.frame().to_local(p);
  return std::abs(l.z - by.g(l.x, l.y));
}

bool same_sample(const LocalPolynomial& a, const LocalPolynomial& b) { return a.origin == b.origin; }

// Every local polynomial of a noisy torus (curved, uneven: some samples lie off their
// neighbours' graphs), sampled 10:1 unevenly with adaptive support: each ball's radius b_k
// is its own.
std::vector<LocalPolynomial> torus_locals(float& h) {
  test::SampleOptions o;
  o.count = 3000;
  o.noise = 0.01f;
  o.nonuniform = true;
  const PointCloud cloud = test::sample(test::Torus{}, o);
  h = test::suggested_h(cloud);
  RayPssParams params = RayPssParams::from_h(h);
  params.projection.support = Support::adaptive;
  params.ball_spacing = 0;
  Stats stats;
  const PreparedCloud prepared(cloud, params, Backend::cpu, stats);
  return {prepared.locals().begin(), prepared.locals().end()};
}

TEST(Thinning, EveryDroppedSampleLiesOnAKeptNeighboursGraphAndNoKeptOneOnAnothers) {
  float h = 0;
  const std::vector<LocalPolynomial> all = torus_locals(h);
  // Per unit of each kept ball's radius b_k, which varies over the torus by some 2:1.
  const float spacing = 0.5f, tolerance = kThinningTolerance;
  const auto [least, largest] = std::minmax_element(all.begin(), all.end(), [](const auto& a, const auto& b) { return a.radius < b.radius; });
  ASSERT_GT(largest->radius, 1.3f * least->radius);
  const std::vector<LocalPolynomial> kept = thin_local_polynomials(all, spacing, tolerance);
  ASSERT_GT(kept.size(), 0u);
  EXPECT_LT(kept.size(), all.size() * 3 / 4);
  std::size_t dropped = 0;
  for (const LocalPolynomial& j : all) {
    bool is_kept = false, represented = false;
    for (const LocalPolynomial& k : kept) {
      if (same_sample(j, k)) is_kept = true;
      else if (glm::length(j.origin - k.origin) <= spacing * k.radius && off_graph(k, j.origin) <= tolerance * k.radius)
        represented = true;
    }
    if (is_kept) continue;
    ++dropped;
    EXPECT_TRUE(represented) << "a dropped sample at " << j.origin.x << ", " << j.origin.y << ", " << j.origin.z;
  }
  EXPECT_EQ(dropped + kept.size(), all.size());
  // Of two kept samples within the earlier one's spacing, the later one lies off the earlier
  // one's graph.
  int close_pairs = 0;
  for (std::size_t a = 0; a < kept.size(); ++a)
    for (std::size_t b = a + 1; b < kept.size(); ++b) {
      if (!(glm::length(kept[a].origin - kept[b].origin) <= spacing * kept[a].radius)) continue;
      ++close_pairs;
      EXPECT_GT(off_graph(kept[a], kept[b].origin), tolerance * kept[a].radius);
    }
  EXPECT_GT(close_pairs, 0);  // the noise keeps some neighbours: the tolerance is exercised
}

TEST(Thinning, ZeroSpacingKeepsEverySampleInOrder) {
  float h = 0;
  const std::vector<LocalPolynomial> all = torus_locals(h);
  const std::vector<LocalPolynomial> kept = thin_local_polynomials(all, 0.0f, kThinningTolerance);
  ASSERT_EQ(kept.size(), all.size());
  for (std::size_t i = 0; i < all.size(); ++i) EXPECT_TRUE(same_sample(kept[i], all[i]));
}

// Two flat faces 0.3h apart, sampled 0.4h apart like a scan of a thin part: a ray may meet
// either, so each keeps as many polynomials as it would alone.
TEST(Thinning, KeepsBothFacesOfAThinPlate) {
  const float h = 1.0f, spacing = 0.5f * h;
  std::vector<LocalPolynomial> face[2], both;
  for (int f = 0; f < 2; ++f)
    for (int i = 0; i < 40; ++i)
      for (int j = 0; j < 40; ++j) {
        LocalPolynomial l;
        l.origin = vec3(0.4f * h * float(i), 0.4f * h * float(j), 0.3f * h * float(f));
        l.normal = vec3(0, 0, f == 0 ? 1.0f : -1.0f);
        l.radius = h;
        face[f].push_back(l);
        both.push_back(l);
      }
  const std::size_t alone = thin_local_polynomials(face[0], spacing / h, kThinningTolerance).size();
  ASSERT_LE(alone, face[0].size() / 2);  // a flat face thins
  std::size_t on[2] = {0, 0};
  for (const LocalPolynomial& k : thin_local_polynomials(both, spacing / h, kThinningTolerance)) ++on[k.origin.z > 0];
  EXPECT_EQ(on[0], alone);
  EXPECT_EQ(on[1], alone);
}

// The renderer's defaults thin (b/2, kThinningTolerance): on a smooth sphere fewer than half
// of the polynomials stay, and the accuracy tests (render_test, ray_pss_test) run with them.
TEST(Thinning, TheRendererKeepsFewerThanHalfOnASmoothSphere) {
  test::SampleOptions o;
  o.count = 5000;
  const PointCloud cloud = test::sample(test::Sphere{}, o);
  const RayPssParams params = RayPssParams::from_h(test::suggested_h(cloud));
  EXPECT_EQ(params.ball_spacing, 0.5f * params.ball_radius);
  Stats stats;
  const PreparedCloud prepared(cloud, params, Backend::cpu, stats);
  EXPECT_LT(prepared.locals().size(), cloud.size() / 2);
  EXPECT_GT(prepared.locals().size(), cloud.size() / 10);
}

}  // namespace
}  // namespace pss
