// The numerical building blocks against closed-form truth.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "pss/fit/brent.hpp"
#include "pss/fit/conjugate_gradient.hpp"
#include "pss/fit/inverse_power.hpp"
#include "pss/fit/moments.hpp"
#include "pss/fit/polynomial.hpp"
#include "pss/core/frame.hpp"

namespace pss {
namespace {

// Q·diag(l)·Qᵀ for the rotation Q = [u v n] of a random frame.
Sym3 matrix_with_spectrum(const Frame& f, vec3 l) {
  Sym3 m;
  m.add_outer(f.u, l.x);
  m.add_outer(f.v, l.y);
  m.add_outer(f.n, l.z);
  return m;
}

Frame random_frame(std::mt19937& rng) {
  std::normal_distribution<float> g;
  return Frame::from_normal(vec3(0.0f), glm::normalize(vec3(g(rng), g(rng), g(rng))));
}

TEST(InversePower, FindsSmallestEigenvectorOfRandomSpectra) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(0.05f, 1.0f);
  for (int trial = 0; trial < 200; ++trial) {
    const Frame f = random_frame(rng);
    const float small = 0.2f * u(rng) * 0.04f;  // well separated: λ0 ≤ 0.008 < 0.05 ≤ λ1
    const EigenResult r = smallest_eigenvector(matrix_with_spectrum(f, vec3(u(rng), u(rng), small)), vec3(0.0f));
    ASSERT_EQ(r.status, EigenStatus::converged);
    // The wanted vector is f.n up to sign; float rounding bounds the angle by ~1e-3 rad.
    EXPECT_GT(std::abs(glm::dot(r.vector, f.n)), 1 - 1e-6f);
    EXPECT_NEAR(r.eigenvalue, small, 1e-5f);
  }
}

TEST(InversePower, PlanarNeighbourhoodHasZeroEigenvalue) {
  std::mt19937 rng(3);
  const Frame f = random_frame(rng);
  // Exactly singular: the shift keeps the factorisation valid.
  const EigenResult r = smallest_eigenvector(matrix_with_spectrum(f, vec3(1.0f, 0.3f, 0.0f)), vec3(0.0f));
  EXPECT_EQ(r.status, EigenStatus::converged);
  EXPECT_GT(std::abs(glm::dot(r.vector, f.n)), 1 - 1e-6f);
}

TEST(InversePower, LinearNeighbourhoodIsDegenerateAndStaysNearStart) {
  std::mt19937 rng(5);
  const Frame f = random_frame(rng);
  // Points on a line along u: any normal orthogonal to u fits; we get the one nearest the start.
  const vec3 start = glm::normalize(f.v + 0.3f * f.u);
  const EigenResult r = smallest_eigenvector(matrix_with_spectrum(f, vec3(1.0f, 0.0f, 0.0f)), start);
  EXPECT_EQ(r.status, EigenStatus::degenerate);
  EXPECT_NEAR(glm::dot(r.vector, f.u), 0.0f, 1e-4f);
  EXPECT_GT(glm::dot(r.vector, f.v), 0.99f);
}

TEST(InversePower, IsotropicSpectrumIsDegenerate) {
  Sym3 m;
  m.xx = m.yy = m.zz = 2.0f;
  EXPECT_EQ(smallest_eigenvector(m, vec3(0, 0, 1)).status, EigenStatus::degenerate);
}

TEST(InversePower, ZeroAndNonFiniteMatricesAreInvalid) {
  EXPECT_EQ(smallest_eigenvector(Sym3{}, vec3(0, 1, 0)).status, EigenStatus::invalid);
  Sym3 m;
  m.xx = NAN;
  const EigenResult r = smallest_eigenvector(m, vec3(0, 1, 0));
  EXPECT_EQ(r.status, EigenStatus::invalid);
  EXPECT_EQ(r.vector, vec3(0, 1, 0));
}

TEST(InversePower, OrientsAlongStartVector) {
  std::mt19937 rng(9);
  const Frame f = random_frame(rng);
  const EigenResult r = smallest_eigenvector(matrix_with_spectrum(f, vec3(1.0f, 0.5f, 0.01f)), -f.n);
  EXPECT_LT(glm::dot(r.vector, f.n), -0.999f);
}

// Gaussian elimination in double: the direct solve CG is checked against.
glm::dvec4 direct_solve(const glm::mat4& m, vec4 b) {
  double a[4][5];
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c) a[r][c] = m[c][r];
    a[r][4] = b[r];
  }
  for (int k = 0; k < 4; ++k) {
    int p = k;
    for (int r = k + 1; r < 4; ++r)
      if (std::abs(a[r][k]) > std::abs(a[p][k])) p = r;
    for (int c = 0; c < 5; ++c) std::swap(a[k][c], a[p][c]);
    for (int r = k + 1; r < 4; ++r) {
      const double f = a[r][k] / a[k][k];
      for (int c = k; c < 5; ++c) a[r][c] -= f * a[k][c];
    }
  }
  glm::dvec4 x;
  for (int k = 3; k >= 0; --k) {
    double s = a[k][4];
    for (int c = k + 1; c < 4; ++c) s -= a[k][c] * x[c];
    x[k] = s / a[k][k];
  }
  return x;
}

TEST(ConjugateGradient, MatchesDirectSolveOnRandomSpdSystems) {
  std::mt19937 rng(11);
  std::normal_distribution<float> g;
  for (int trial = 0; trial < 500; ++trial) {
    // M = BᵀB + 0.1·I: SPD with condition number up to ~10³.
    glm::mat4 b;
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r) b[c][r] = g(rng);
    glm::mat4 m = glm::transpose(b) * b;
    for (int i = 0; i < 4; ++i) m[i][i] += 0.1f;
    const vec4 rhs(g(rng), g(rng), g(rng), g(rng));
    const CgResult cg = conjugate_gradient(m, rhs, 16, 1e-7f);
    const glm::dvec4 x = direct_solve(m, rhs);
    // Forward error ≤ cond·ε_float ≈ 10³·6e-8 relative to ‖x‖.
    const double scale = glm::length(x);
    for (int i = 0; i < 4; ++i) EXPECT_NEAR(cg.x[i], x[i], 1e-3 * scale) << "trial " << trial;
  }
}

TEST(ConjugateGradient, SingularConsistentSystemGivesMinimumNormSolution) {
  // Rank 2: x and y each appear in one equation, z and w in none.
  glm::mat4 m(0.0f);
  m[0][0] = 2;
  m[1][1] = 4;
  const CgResult r = conjugate_gradient(m, vec4(2, 8, 0, 0));
  EXPECT_NEAR(r.x.x, 1, 1e-6);
  EXPECT_NEAR(r.x.y, 2, 1e-6);
  EXPECT_EQ(r.x.z, 0);
  EXPECT_EQ(r.x.w, 0);
}

// Point by point (add) and in SIMD lanes (add_all), the same exact quadratic.
TEST(PolynomialFit, RecoversExactQuadraticAtAnyScale) {
  for (bool batched : {false, true}) {
    for (float scale : {1e-3f, 1.0f, 1e3f}) {
      const Polynomial truth{0.7f / scale, -0.4f / scale, 0.25f / scale, 0.1f * scale};
      PolynomialFit fit(scale);
      std::mt19937 rng(2);
      std::uniform_real_distribution<float> u(-2 * scale, 2 * scale);
      std::vector<vec3> points;
      std::vector<float> weights;
      for (int i = 0; i < 50; ++i) {
        const float x = u(rng), y = u(rng);
        points.push_back(vec3(x, y, truth(x, y)));
        weights.push_back(0.5f + 0.01f * i);
      }
      // add_all reads up to the next multiple of the lanes, where the weights must be 0.
      points.resize(50 + PSS_SUM_LANES, vec3(0.0f));
      weights.resize(points.size(), 0.0f);
      if (batched)
        fit.add_all(50, [&](int i) { return points[i]; }, [&](int i) { return weights[i]; });
      else
        for (int i = 0; i < 50; ++i) fit.add(points[i], weights[i]);
      EXPECT_EQ(fit.count, 50);
      const Polynomial g = fit.solve();
      EXPECT_NEAR(g.a * scale, truth.a * scale, 1e-4) << batched;
      EXPECT_NEAR(g.b * scale, truth.b * scale, 1e-4) << batched;
      EXPECT_NEAR(g.c * scale, truth.c * scale, 1e-4) << batched;
      EXPECT_NEAR(g.d / scale, truth.d / scale, 1e-5) << batched;
    }
  }
}

// The sums of WeightedMoments::add_all against the same sums in double precision.
TEST(WeightedMoments, AddAllSumsLikeDoublePrecision) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f), w(0.0f, 1.0f);
  const vec3 origin(10.0f, -3.0f, 2.0f);
  std::vector<vec3> d(101);
  std::vector<float> weight(d.size());
  double sw = 0, first[3] = {0, 0, 0}, second[3][3] = {};
  for (std::size_t i = 0; i < d.size(); ++i) {
    d[i] = vec3(u(rng), u(rng), u(rng));
    weight[i] = w(rng);
    sw += weight[i];
    for (int a = 0; a < 3; ++a) {
      first[a] += double(weight[i]) * d[i][a];
      for (int b = 0; b < 3; ++b) second[a][b] += double(weight[i]) * d[i][a] * d[i][b];
    }
  }
  WeightedMoments m(origin);
  const int n = int(d.size());
  // add_all reads up to the next multiple of the lanes, where the weights must be 0.
  d.resize(d.size() + PSS_SUM_LANES, vec3(0.0f));
  weight.resize(d.size(), 0.0f);
  m.add_all(n, [&](int i) { return d[i]; }, [&](int i) { return weight[i]; });
  EXPECT_EQ(m.count, 101);
  const double tol = 1e-5 * sw;
  EXPECT_NEAR(m.weight_sum, sw, tol);
  for (int a = 0; a < 3; ++a) EXPECT_NEAR(m.first[a], first[a], tol);
  EXPECT_NEAR(m.second.xx, second[0][0], tol);
  EXPECT_NEAR(m.second.xy, second[0][1], tol);
  EXPECT_NEAR(m.second.xz, second[0][2], tol);
  EXPECT_NEAR(m.second.yy, second[1][1], tol);
  EXPECT_NEAR(m.second.yz, second[1][2], tol);
  EXPECT_NEAR(m.second.zz, second[2][2], tol);
  // The offsets are from the origin: the mean is the origin plus the weighted mean offset.
  for (int a = 0; a < 3; ++a) EXPECT_NEAR(m.mean()[a], origin[a] + first[a] / sw, 1e-5);
}

// The branch-free exp of the Gaussian weights against exp in double precision, at every
// float of [−87, 0] taken 1 in 1024 (every exponent, and a million arguments).
TEST(ExpNonpositive, WithinTwoUlpOfExp) {
  double worst = 0;
  float worst_x = 0;
  // Negative floats grow in magnitude with their bit pattern: walk it from −87 to −0.
  for (std::uint32_t bits = std::bit_cast<std::uint32_t>(-87.0f); bits >= 0x80000000u; bits -= 1024) {
    const float x = std::bit_cast<float>(bits);
    const double truth = std::exp(double(x));
    const double ulp = std::ldexp(1.0, std::ilogb(truth) - 23);
    const double error = std::abs(double(exp_nonpositive(x)) - truth) / ulp;
    if (error > worst) {
      worst = error;
      worst_x = x;
    }
  }
  EXPECT_LE(worst, 1.0) << "at x = " << worst_x;  // 0.99 ulp over every float of [−87, 0]
  EXPECT_EQ(exp_nonpositive(0.0f), 1.0f);
  // Below the normal range: tiny and not negative, never a wrapped exponent.
  for (float x : {-87.5f, -100.0f, -1e4f}) {
    EXPECT_GE(exp_nonpositive(x), 0.0f);
    EXPECT_LT(exp_nonpositive(x), std::ldexp(1.0f, -125));
  }
}

TEST(PolynomialFit, FewNeighboursFallBackToWeightedPlane) {
  PolynomialFit fit(1.0f);
  fit.add(vec3(0, 0, 1), 1);
  fit.add(vec3(1, 0, 3), 1);
  const Polynomial g = fit.solve();
  EXPECT_FLOAT_EQ(g.d, 2);
  EXPECT_EQ(g.a, 0);
}

// The foot point of the origin against a brute-force search of the graph: (0, 0, D) is the
// nearest point exactly when I + D·∇²g is positive definite (polynomial.hpp); otherwise
// some point off the axis is nearer and the function says so.
TEST(ProjectOriginOntoGraph, MatchesBruteForceAndRefusesBeyondTheCentreOfCurvature) {
  std::mt19937 rng(4);
  std::uniform_real_distribution<float> u(-1.5f, 1.5f);
  int refused = 0, accepted = 0;
  for (int i = 0; i < 200; ++i) {
    const Polynomial g{u(rng), u(rng), u(rng), u(rng)};
    // The smallest eigenvalue of I + D·∇²g; near 0 the grid cannot tell the two apart.
    const float hxx = 1 + 2 * g.a * g.d, hyy = 1 + 2 * g.b * g.d, hxy = g.c * g.d;
    const float margin = 0.5f * (hxx + hyy) - std::sqrt(0.25f * (hxx - hyy) * (hxx - hyy) + hxy * hxy);
    if (std::abs(margin) < 0.05f) continue;
    float best = kInfinity;
    for (float x = -3; x <= 3; x += 0.01f)
      for (float y = -3; y <= 3; y += 0.01f) best = std::min(best, x * x + y * y + g(x, y) * g(x, y));
    vec3 foot;
    const bool projected = project_origin_onto_graph(g, foot);
    EXPECT_EQ(foot, vec3(0.0f, 0.0f, g.d));
    const float axis = g.d * g.d;
    if (projected) {
      ++accepted;
      EXPECT_LE(axis, best + 1e-4f) << i;  // nothing on the graph is nearer
    } else {
      ++refused;
      EXPECT_LT(best, axis - 1e-6f) << i;  // a point off the axis is nearer
    }
  }
  EXPECT_GT(accepted, 20);
  EXPECT_GT(refused, 20);
}

TEST(IntersectGraph, RootsSolveTheEquation) {
  const Polynomial g{0.5f, 0.2f, -0.1f, 0.05f};
  const vec3 o(0.1f, -0.2f, 2.0f), d = glm::normalize(vec3(0.1f, 0.05f, -1.0f));
  float t[2];
  const int n = intersect_graph(g, o, d, t);
  ASSERT_EQ(n, 2);
  for (int i = 0; i < n; ++i) {
    const vec3 p = o + t[i] * d;
    EXPECT_NEAR(p.z, g(p.x, p.y), 1e-6f * (1 + std::abs(p.z)));
  }
  // The near root: the graph is ~0.07 high around (0.3, −0.1), 2 − 0.07 below the origin
  // along a direction with d.z ≈ −0.994. The far root is behind the origin.
  EXPECT_LT(t[0], 0);
  EXPECT_NEAR(t[1], 1.93f / 0.994f, 0.03f);
}

// graph_crossed against the roots themselves: the same answer wherever no root lies within
// rounding of the interval's ends, on random quadratics, planes and rays, two-root cases included.
TEST(IntersectGraph, CrossedExactlyWhenARootLiesInTheInterval) {
  std::mt19937 rng(9);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f), span_of(0.01f, 2.0f);
  int crossed = 0, missed = 0, two_inside = 0;
  for (int i = 0; i < 200000; ++i) {
    const Polynomial g{u(rng), u(rng), u(rng), 0.2f * u(rng)};
    const Polynomial plane{0, 0, 0, 0.2f * u(rng)};
    const Polynomial& p = i % 10 == 0 ? plane : g;
    const vec3 o(u(rng), u(rng), 0.3f * u(rng));
    const vec3 d = glm::normalize(vec3(u(rng), u(rng), u(rng)));
    const float span = span_of(rng);
    float roots[2];
    const int n = intersect_graph(p, o, d, roots);
    bool inside = false, near_end = false;
    int count = 0;
    for (int k = 0; k < n; ++k) {
      inside |= roots[k] >= 0 && roots[k] <= span;
      count += roots[k] >= 0 && roots[k] <= span;
      near_end |= std::abs(roots[k]) < 1e-4f || std::abs(roots[k] - span) < 1e-4f;
    }
    if (near_end) continue;
    ASSERT_EQ(graph_crossed(p, o, d, span), inside) << i;
    crossed += inside;
    missed += !inside;
    two_inside += count == 2;
  }
  EXPECT_GT(crossed, 10000);
  EXPECT_GT(missed, 10000);
  EXPECT_GT(two_inside, 500);
}

TEST(IntersectGraph, PlaneAndMiss) {
  float t[2];
  EXPECT_EQ(intersect_graph(Polynomial{0, 0, 0, 1}, vec3(0, 0, 3), vec3(0, 0, -1), t), 1);
  EXPECT_FLOAT_EQ(t[0], 2);
  // Paraboloid opening up, ray above it going sideways: no root.
  EXPECT_EQ(intersect_graph(Polynomial{1, 1, 0, 0}, vec3(0, 0, -1), vec3(1, 0, 0), t), 0);
}

TEST(Brent, MinimisesWithDerivative) {
  int calls = 0;
  auto f = [&](float x, float& df) {
    ++calls;
    df = 4 * (x - 0.3f) * (x - 0.3f) * (x - 0.3f) + 2 * (x - 0.3f);
    return (x - 0.3f) * (x - 0.3f) * (x - 0.3f) * (x - 0.3f) + (x - 0.3f) * (x - 0.3f);
  };
  const BrentResult r = brent_minimize(f, -1.0f, 2.0f, -0.8f, 1e-6f);
  EXPECT_NEAR(r.x, 0.3f, 1e-5);
  EXPECT_EQ(r.evaluations, calls);
  // Secant steps on f' (10 evaluations here); bisection alone takes 22 to the tolerance.
  EXPECT_LE(calls, 14);
}

// On a parabola f' is a line: the first secant step lands on the minimum (4 evaluations in
// all, where bisection takes 22).
TEST(Brent, AParabolasMinimumInAFewSteps) {
  int calls = 0;
  auto f = [&](float x, float& df) {
    ++calls;
    df = 2 * (x - 1.234f);
    return (x - 1.234f) * (x - 1.234f);
  };
  EXPECT_NEAR(brent_minimize(f, -1.0f, 2.0f, -0.8f, 1e-6f).x, 1.234f, 1e-5);
  EXPECT_LE(calls, 6);
}

TEST(Brent, MinimumAtTheIntervalEnd) {
  auto f = [](float x, float& df) {
    df = 1;
    return x;
  };
  EXPECT_NEAR(brent_minimize(f, 0.0f, 1.0f, 0.5f, 1e-6f).x, 0.0f, 1e-5);
}

}  // namespace
}  // namespace pss
