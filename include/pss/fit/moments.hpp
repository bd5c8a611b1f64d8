// Weighted sums over a neighbourhood: Σw, Σw·p and Σw·p·pᵀ, taken relative to an origin
// near the points so that single precision keeps its digits.
#pragma once

#include "pss/core/types.hpp"

namespace pss {

// Symmetric 3×3 matrix stored as its upper triangle.
struct Sym3 {
  float xx = 0, xy = 0, xz = 0, yy = 0, yz = 0, zz = 0;

  PSS_HOST_DEVICE void add_outer(vec3 d, float w) {
    xx += w * d.x * d.x;
    xy += w * d.x * d.y;
    xz += w * d.x * d.z;
    yy += w * d.y * d.y;
    yz += w * d.y * d.z;
    zz += w * d.z * d.z;
  }
  PSS_HOST_DEVICE vec3 operator*(vec3 v) const {
    return vec3(xx * v.x + xy * v.y + xz * v.z, xy * v.x + yy * v.y + yz * v.z,
                xz * v.x + yz * v.y + zz * v.z);
  }
  PSS_HOST_DEVICE Sym3 scaled(float s) const { return {xx * s, xy * s, xz * s, yy * s, yz * s, zz * s}; }
  PSS_HOST_DEVICE float trace() const { return xx + yy + zz; }
};

struct WeightedMoments {
  vec3 origin{0.0f};
  float weight_sum = 0;
  vec3 first{0.0f};  // Σ w (p - origin)
  Sym3 second;       // Σ w (p - origin)(p - origin)ᵀ
  int count = 0;

  PSS_HOST_DEVICE explicit WeightedMoments(vec3 o) : origin(o) {}

  PSS_HOST_DEVICE void add(vec3 p, float w) {
    const vec3 d = p - origin;
    weight_sum += w;
    first += w * d;
    second.add_outer(d, w);
    ++count;
  }
  // add(origin + offset(i), weight(i)) for i < n, summed in SIMD lanes on the CPU.
  template <class Offset, class Weight>
  PSS_HOST_DEVICE void add_all(int n, Offset&& offset, Weight&& weight) {
    float sw = 0, fx = 0, fy = 0, fz = 0, xx = 0, xy = 0, xz = 0, yy = 0, yz = 0, zz = 0;
    PSS_SIMD_SUM(sw, fx, fy, fz, xx, xy, xz, yy, yz, zz)
    for (int i = 0; i < n; ++i) {
      const vec3 d = offset(i);
      const float w = weight(i);
      sw += w;
      fx += w * d.x;
      fy += w * d.y;
      fz += w * d.z;
      xx += w * d.x * d.x;
      xy += w * d.x * d.y;
      xz += w * d.x * d.z;
      yy += w * d.y * d.y;
      yz += w * d.y * d.z;
      zz += w * d.z * d.z;
    }
    weight_sum += sw;
    first += vec3(fx, fy, fz);
    second.xx += xx;
    second.xy += xy;
    second.xz += xz;
    second.yy += yy;
    second.yz += yz;
    second.zz += zz;
    count += n;
  }
  PSS_HOST_DEVICE vec3 mean() const { return origin + first / weight_sum; }

  // Σw(p - m)(p - m)ᵀ / Σw: the matrix whose smallest eigenvector is the normal of the
  // plane that minimises Eq. 1 for fixed weights.
  PSS_HOST_DEVICE Sym3 covariance_about_mean() const {
    const vec3 m = first / weight_sum;
    Sym3 c = second.scaled(1.0f / weight_sum);
    c.add_outer(m, -1.0f);
    return c;
  }
  // Σw(p - o)(p - o)ᵀ / Σw: the paper's C1(q), C2(P(r)) with the plane forced through o.
  PSS_HOST_DEVICE Sym3 covariance_about_origin() const { return second.scaled(1.0f / weight_sum); }
};

}  // namespace pss
