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
  float inv_h2_sum = 0;  // Σ w/h² of the samples' own widths, where they have them (points/neighbourhood.hpp)

  PSS_HOST_DEVICE explicit WeightedMoments(vec3 o) : origin(o) {}

  PSS_HOST_DEVICE void add(vec3 p, float w) { add_offset(p - origin, w); }
  // add(origin + d, w), with d as given.
  PSS_HOST_DEVICE void add_offset(vec3 d, float w) {
    weight_sum += w;
    first += w * d;
    second.add_outer(d, w);
    ++count;
  }
  // add(origin + offset(i), weight(i)) for i < n, summed in PSS_SUM_LANES lanes. Both are
  // read up to n rounded up to a multiple of the lanes, where offset must be finite and
  // weight 0.
  template <class Offset, class Weight>
  PSS_HOST_DEVICE void add_all(int n, Offset&& offset, Weight&& weight) {
    constexpr int L = PSS_SUM_LANES;
    float sw[L] = {}, fx[L] = {}, fy[L] = {}, fz[L] = {};
    float xx[L] = {}, xy[L] = {}, xz[L] = {}, yy[L] = {}, yz[L] = {}, zz[L] = {};
    for (int i0 = 0; i0 < n; i0 += L) {
      for (int l = 0; l < L; ++l) {
        const vec3 d = offset(i0 + l);
        const float w = weight(i0 + l);
        sw[l] += w;
        fx[l] += w * d.x;
        fy[l] += w * d.y;
        fz[l] += w * d.z;
        xx[l] += w * d.x * d.x;
        xy[l] += w * d.x * d.y;
        xz[l] += w * d.x * d.z;
        yy[l] += w * d.y * d.y;
        yz[l] += w * d.y * d.z;
        zz[l] += w * d.z * d.z;
      }
    }
    for (int l = 0; l < L; ++l) {
      weight_sum += sw[l];
      first += vec3(fx[l], fy[l], fz[l]);
      second.xx += xx[l];
      second.xy += xy[l];
      second.xz += xz[l];
      second.yy += yy[l];
      second.yz += yz[l];
      second.zz += zz[l];
    }
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
