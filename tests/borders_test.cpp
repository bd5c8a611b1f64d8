// Where the surface ends (issue 26, points/borders.hpp): a point counts as surface among its
// samples, not on the band the projection extrapolates past the last of them.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "pss/points/borders.hpp"
#include "support/render_truth.hpp"

namespace pss {
namespace {

// A neighbourhood of given points, as samples_surround reads one (neighbourhood.hpp), each of
// width h (by default wider than the sets below: only the hull decides).
struct Points {
  std::vector<vec3> p;
  std::vector<float> h = {};
  template <class F>
  void for_each(F&& f) const {
    for (std::size_t i = 0; i < p.size(); ++i) {
      const float width = i < h.size() ? h[i] : 100.0f;
      f(p[i], 1.0f, 1.0f / (width * width), 1.0f);
    }
  }
};

// The widest gap between the directions from x to the points, in degrees (brute force).
double widest_gap_deg(const std::vector<glm::dvec2>& points, glm::dvec2 x) {
  std::vector<double> angles;
  for (const glm::dvec2& p : points) angles.push_back(std::atan2(p.y - x.y, p.x - x.x) * 180 / 3.14159265358979);
  std::sort(angles.begin(), angles.end());
  double widest = angles.front() + 360 - angles.back();
  for (std::size_t i = 1; i < angles.size(); ++i) widest = std::max(widest, angles[i] - angles[i - 1]);
  return widest;
}

// Against the exact test, on random sets in a tilted plane: a point whose widest gap is
// under 180° lies inside the samples' hull and is surrounded; one whose widest gap is over
// 180° + 7.2° (one of the coarsest bins) is not. Both kinds occur often.
TEST(Borders, SurroundedExactlyWhereTheSamplesHoldThePoint) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> uni(-1, 1);
  const glm::dvec3 n = glm::normalize(glm::dvec3(0.3, -0.5, 0.8));
  const glm::dvec3 u = glm::normalize(glm::cross(n, glm::dvec3(1, 0, 0))), v = glm::cross(n, u);
  const auto lift = [&](glm::dvec2 q, double off) { return vec3(q.x * u + q.y * v + off * n + glm::dvec3(5, -2, 3)); };
  int inside = 0, outside = 0;
  for (int trial = 0; trial < 300; ++trial) {
    std::vector<glm::dvec2> flat;
    Points samples;
    const int count = 3 + trial % 40;
    for (int i = 0; i < count; ++i) {
      flat.emplace_back(uni(rng), 0.5 * uni(rng));
      samples.p.push_back(lift(flat.back(), 0.05 * uni(rng)));  // a little off the plane: noise
    }
    for (int q = 0; q < 20; ++q) {
      const glm::dvec2 x(1.3 * uni(rng), 0.8 * uni(rng));
      const double gap = widest_gap_deg(flat, x);
      const bool surrounded = samples_surround(samples, lift(x, 0), vec3(n));
      if (gap < 179.9) {
        ++inside;
        EXPECT_TRUE(surrounded) << "gap " << gap;
      } else if (gap > 187.3) {
        ++outside;
        EXPECT_FALSE(surrounded) << "gap " << gap;
      }
    }
  }
  EXPECT_GT(inside, 1000);
  EXPECT_GT(outside, 1000);
}

TEST(Borders, NoSamplesOrOnlyTheNormalsLineSurroundNothing) {
  EXPECT_FALSE(samples_surround(Points{}, vec3(0.0f), vec3(0, 0, 1)));
  EXPECT_FALSE(samples_surround(Points{{vec3(0, 0, 1), vec3(0, 0, -1)}}, vec3(0.0f), vec3(0, 0, 1)));
  EXPECT_TRUE(samples_surround(Points{{vec3(1, 0, 0), vec3(-1, 1, 0), vec3(-1, -1, 0)}}, vec3(0.0f), vec3(0, 0, 1)));
  // Samples all on one side, and one straight above x (another sheet): still a border.
  EXPECT_FALSE(samples_surround(Points{{vec3(-1, 0.2f, 0), vec3(-1, -0.2f, 0), vec3(0, 0, 0.5f)}}, vec3(0.0f),
                                vec3(0, 0, 1)));
}

// Surrounded, but farther than its width from every sample, a point is no surface (a hole
// the supports of its rim span): each sample by its own width.
TEST(Borders, APointBeyondEverySamplesWidthIsNoSurface) {
  const std::vector<vec3> ring = {vec3(1.2f, 0, 0), vec3(-0.6f, 1.04f, 0), vec3(-0.6f, -1.04f, 0)};
  const vec3 up(0, 0, 1), x(0.0f);
  EXPECT_FALSE(samples_surround(Points{ring, {1.0f, 1.0f, 1.0f}}, x, up));
  EXPECT_TRUE(samples_surround(Points{ring, {1.25f, 1.25f, 1.25f}}, x, up));
  EXPECT_TRUE(samples_surround(Points{ring, {1.0f, 1.0f, 1.25f}}, x, up));  // one within its width
  EXPECT_FALSE(samples_surround(Points{ring, {1.0f, 1.0f, 1.15f}}, x, up));
}

// An open square rendered: clipped, no hit lies past its samples by more than the bins'
// sliver (about ρ/16); extended, the paper's surface runs on about a ball past the edge.
// Inside, both show the square whole, for MLS and RIMLS.
TEST(Borders, AnOpenSquareEndsAtItsSamplesWhenClipped) {
  for (const SurfaceOperator surface : {SurfaceOperator::mls, SurfaceOperator::rimls}) {
    const test::BorderTruth clip = test::render_open_square(BorderMode::clip, surface, Backend::cpu);
    const test::BorderTruth extend = test::render_open_square(BorderMode::extend, surface, Backend::cpu);
    std::printf("%s: clip %lld past the edge (farthest %.2f h), %lld holes; extend %lld (%.2f h), %lld holes\n",
                surface_name(surface), (long long)clip.beyond, clip.overshoot, (long long)clip.holes,
                (long long)extend.beyond, extend.overshoot, (long long)extend.holes);
    ASSERT_GT(clip.inner_pixels, 6000);
    EXPECT_EQ(clip.holes, 0);
    EXPECT_EQ(extend.holes, 0);
    EXPECT_LT(clip.overshoot, 0.25);
    EXPECT_GT(extend.overshoot, 0.5);
    EXPECT_GT(extend.beyond, 200);
  }
}

// A hemisphere open at z = 0 with one projection per candidate: on its curve few candidates
// are within ε at once, so most hits are the last iterate, and those past the rim are refused
// too.
TEST(Borders, CappedHitsEndAtTheSamplesToo) {
  test::SampleOptions o;
  o.count = 8000;
  PointCloud cloud;
  for (const vec3& p : test::sample(test::Sphere{}, o).positions)
    if (p.z > 0) cloud.positions.push_back(p);
  const float h = test::suggested_h(cloud);
  const auto past_the_rim = [&](BorderMode borders) {
    RayPssParams params = RayPssParams::from_h(h);
    params.projection.borders = borders;
    params.max_iterations = 1;
    const RenderedFrame frame = test::render_at_160(cloud, params, Backend::cpu, cloud.bounds(), 30, -20, vec3(0, 0, 1));
    std::int64_t past = 0, capped = 0;
    for (const Hit& hit : frame.hits) {
      past += hit.found() && hit.point.z < -0.25f * h;
      capped += hit.found() && (hit.flags & kHitCapped) != 0;
    }
    std::printf("%s: %lld hits past the rim, %lld capped\n", border_name(borders), (long long)past, (long long)capped);
    return past;
  };
  EXPECT_EQ(past_the_rim(BorderMode::clip), 0);
  EXPECT_GT(past_the_rim(BorderMode::extend), 100);
}

}  // namespace
}  // namespace pss
