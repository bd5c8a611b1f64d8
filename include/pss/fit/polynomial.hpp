// The local bivariate polynomial g(x, y) = Ax² + By² + Cxy + D on the plane H(n, q)
// (paper §3, §4), its weighted least-squares fit, the orthogonal projection of the frame's
// origin onto its graph, and the intersection of a ray with it. Coordinates are local to a Frame.
#pragma once

#include "pss/fit/conjugate_gradient.hpp"

namespace pss {

struct Polynomial {
  float a = 0, b = 0, c = 0, d = 0;

  PSS_HOST_DEVICE float operator()(float x, float y) const { return a * x * x + b * y * y + c * x * y + d; }
  PSS_HOST_DEVICE vec2 gradient(float x, float y) const { return vec2(2 * a * x + c * y, 2 * b * y + c * x); }
  // Unit normal of the graph z = g(x, y), in local coordinates, pointing to +z.
  PSS_HOST_DEVICE vec3 normal(float x, float y) const {
    const vec2 g = gradient(x, y);
    return glm::normalize(vec3(-g.x, -g.y, 1.0f));
  }
};

// Accumulates the normal equations Σw·aaᵀ c = Σw·a·z with a = [x², y², xy, 1]. x and y are
// divided by `scale` (h) first, so the matrix entries are of order one for any units.
struct PolynomialFit {
  float inv_scale;
  glm::mat4 normal_matrix{0.0f};
  vec4 rhs{0.0f};
  float weight_sum = 0;
  float weighted_height = 0;
  int count = 0;

  PSS_HOST_DEVICE explicit PolynomialFit(float scale) : inv_scale(1.0f / scale) {}

  PSS_HOST_DEVICE void add(vec3 local, float w) {
    const float x = local.x * inv_scale, y = local.y * inv_scale;
    const vec4 row(x * x, y * y, x * y, 1.0f);
    for (int c = 0; c < 4; ++c) normal_matrix[c] += (w * row[c]) * row;
    rhs += (w * local.z) * row;
    weight_sum += w;
    weighted_height += w * local.z;
    ++count;
  }

  // add(local(i), weight(i)) for i < n, summed in PSS_SUM_LANES lanes. Both are read up to
  // n rounded up to a multiple of the lanes, where local must be finite and weight 0.
  template <class Local, class Weight>
  PSS_HOST_DEVICE void add_all(int n, Local&& local, Weight&& weight) {
    constexpr int L = PSS_SUM_LANES;
    // The distinct entries of Σw·aaᵀ (x²y² appears twice) and of Σw·a·z.
    float x4[L] = {}, x2y2[L] = {}, x3y[L] = {}, x2[L] = {}, y4[L] = {}, xy3[L] = {}, y2[L] = {}, xy[L] = {};
    float w1[L] = {}, zx2[L] = {}, zy2[L] = {}, zxy[L] = {}, z1[L] = {};
    const float s = inv_scale;
    for (int i0 = 0; i0 < n; i0 += L) {
      for (int l = 0; l < L; ++l) {
        const vec3 p = local(i0 + l);
        const float w = weight(i0 + l);
        const float x = p.x * s, y = p.y * s;
        const float wxx = w * x * x, wyy = w * y * y, wxy = w * x * y;
        x4[l] += wxx * x * x;
        x2y2[l] += wxx * y * y;
        x3y[l] += wxx * x * y;
        x2[l] += wxx;
        y4[l] += wyy * y * y;
        xy3[l] += wyy * x * y;
        y2[l] += wyy;
        xy[l] += wxy;
        w1[l] += w;
        zx2[l] += wxx * p.z;
        zy2[l] += wyy * p.z;
        zxy[l] += wxy * p.z;
        z1[l] += w * p.z;
      }
    }
    for (int l = 0; l < L; ++l) {
      // Columns of the symmetric matrix for rows (x², y², xy, 1).
      normal_matrix[0] += vec4(x4[l], x2y2[l], x3y[l], x2[l]);
      normal_matrix[1] += vec4(x2y2[l], y4[l], xy3[l], y2[l]);
      normal_matrix[2] += vec4(x3y[l], xy3[l], x2y2[l], xy[l]);
      normal_matrix[3] += vec4(x2[l], y2[l], xy[l], w1[l]);
      rhs += vec4(zx2[l], zy2[l], zxy[l], z1[l]);
      weight_sum += w1[l];
      weighted_height += z1[l];
    }
    count += n;
  }

  // With fewer than six neighbours the three curvature terms are not determined: fall back
  // to the plane through the weighted mean height (A = B = C = 0).
  PSS_HOST_DEVICE Polynomial solve() const {
    Polynomial g;
    if (!(weight_sum > 0)) return g;
    if (count < 6) {
      g.d = weighted_height / weight_sum;
      return g;
    }
    const vec4 x = conjugate_gradient(normal_matrix, rhs).x;
    const float s2 = inv_scale * inv_scale;
    g.a = x.x * s2;
    g.b = x.y * s2;
    g.c = x.z * s2;
    g.d = x.w;
    return g;
  }
};

// The orthogonal projection of the frame's origin onto the graph of g (§4: "the projection
// of q on the local approximation"). g has no linear terms, so along every direction u of
// the plane the squared distance |u|² + (uᵀMu + D)² (g = uᵀMu + D) grows with s = |u|² at
// the rate 1 + 2λ(λs + D) ≥ 1 + 2λD, λ = ûᵀMû: the foot point is (0, 0, D) exactly when
// 1 + 2λD > 0 for every λ, i.e. I + D·∇²g is positive definite, the origin on the near side
// of every centre of curvature. Otherwise the nearest point lies off the axis (or is not
// unique): false, with `foot` still (0, 0, D).
PSS_INLINE bool project_origin_onto_graph(const Polynomial& g, vec3& foot) {
  foot = vec3(0.0f, 0.0f, g.d);
  const float hxx = 1 + 2 * g.a * g.d, hyy = 1 + 2 * g.b * g.d, hxy = g.c * g.d;
  return hxx > 0 && hxx * hyy - hxy * hxy > 0;
}

// Whether g(o + t·d) = (o + t·d).z has a root t in [0, span], without solving for it (no
// square root, no division where the answer is no): a sign change between the ends, or the
// same sign at both ends with the parabola's vertex between them and across zero.
PSS_INLINE bool graph_crossed(const Polynomial& g, vec3 o, vec3 d, float span) {
  const float a2 = g.a * d.x * d.x + g.b * d.y * d.y + g.c * d.x * d.y;
  const float a1 = 2 * g.a * o.x * d.x + 2 * g.b * o.y * d.y + g.c * (o.x * d.y + o.y * d.x) - d.z;
  const float a0 = g(o.x, o.y) - o.z;
  const float end = (a2 * span + a1) * span + a0;
  if (!(a0 * end > 0)) return true;            // a sign change, a root at an end, or NaN
  if (!(a2 * a0 > 0)) return false;            // opening away from zero: the vertex keeps the sign
  if (a1 * a1 - 4 * a2 * a0 < 0) return false; // the vertex does not reach zero
  const float vertex = -a1 / (2 * a2);
  return vertex > 0 && vertex < span;
}

// Roots t of g(o + t·d) = (o + t·d).z in increasing order (local coordinates); returns how
// many (0, 1 or 2). Uses the cancellation-free form of the quadratic formula.
PSS_INLINE int intersect_graph(const Polynomial& g, vec3 o, vec3 d, float roots[2]) {
  const float a2 = g.a * d.x * d.x + g.b * d.y * d.y + g.c * d.x * d.y;
  const float a1 = 2 * g.a * o.x * d.x + 2 * g.b * o.y * d.y + g.c * (o.x * d.y + o.y * d.x) - d.z;
  const float a0 = g(o.x, o.y) - o.z;
  const float linear_scale = abs(a1) + abs(a0);
  if (abs(a2) <= 1e-7f * linear_scale) {  // (nearly) a plane: one root
    if (a1 == 0) return 0;
    roots[0] = -a0 / a1;
    return 1;
  }
  const float disc = a1 * a1 - 4 * a2 * a0;
  if (disc < 0) return 0;
  const float qq = -0.5f * (a1 + copysign(sqrt(disc), a1));
  float t0 = qq / a2;
  float t1 = qq != 0 ? a0 / qq : t0;
  if (t0 > t1) swap(t0, t1);
  roots[0] = t0;
  roots[1] = t1;
  return 2;
}

}  // namespace pss
