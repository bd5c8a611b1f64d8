// Where the surface of an open cloud ends (issue 26). The projection extrapolates, so without
// a bound the PSS runs on past the last samples of an open rim, a scan's border or a thin
// part's edge, a band about a ball wide (the locally refined cylinder: 10–20 % of its pixels
// extra). A point of the surface counts where its samples surround it, in its tangent plane:
// no half-plane through it is empty of N(x), i.e. it lies inside their convex hull there.
// Inside the data the samples lie on every side; beyond the last ones they all lie behind.
// And it lies within one width h_j of some sample j: a hole in the data that its rims'
// supports span (the bunny's base) stays open, where the hull test alone laid lids across
// its narrows, up to 1.6 h from any sample, pierced wherever the test flickered (at a
// quarter of the default cell, 60 boundary loops against its scan's 5). A surface point
// of evenly sampled data lies within about a third of h of a sample (h_j ≈ 2.2 spacings;
// the bunny's own triangles reach 0.77 h at most), a gap between rows of samples within
// 0.7 h of their widths (blade.off); 0.8 h already cut into blade's surface.
#pragma once

#include <cstdint>

#include "pss/core/frame.hpp"

namespace pss {

// How far from every sample, in its widths, a point is no surface.
inline constexpr float kSurfaceReach = 1.0f;

namespace detail {

// A monotone stand-in for the angle of (x, y), in [0, 4] ("diamond angle"): no atan2, and
// opposite directions lie exactly 2 apart, so that a half-plane is an interval of length 2.
// NaN for (0, 0).
PSS_INLINE float diamond_angle(float x, float y) {
  if (y >= 0) return x >= 0 ? y / (x + y) : 1 - x / (y - x);
  return x < 0 ? 2 - y / (-x - y) : 3 + x / (x - y);
}

PSS_INLINE std::uint64_t rotate_left(std::uint64_t v, int s) { return (v << s) | (v >> (64 - s)); }

}  // namespace detail

// Whether x, on the surface with `normal`, lies among the samples of `neighbours` (N(r) of a
// projection, neighbourhood.hpp): within kSurfaceReach·h_j of one, and in 64 bins of
// direction in the tangent plane (3.6° to 7.2° wide), no 32 empty in a row, which would be
// an empty half-plane. A gap of up to one bin over 180° may go unseen: x past a straight
// border by up to about ρ/16.
template <class Nb>
PSS_HOST_DEVICE bool samples_surround(const Nb& neighbours, vec3 x, vec3 normal) {
  const Frame frame = Frame::from_normal(x, normal);
  std::uint64_t occupied = 0;
  bool within_reach = false;
  neighbours.for_each([&](vec3 p, float, float inv_h2, float) {
    within_reach = within_reach || length2(p - x) * inv_h2 <= kSurfaceReach * kSurfaceReach;
    const vec3 l = frame.direction_to_local(p - x);
    const float bin = detail::diamond_angle(l.x, l.y) * 16;
    if (!(bin >= 0)) return;  // NaN: straight above or below x, or a normal not finite
    occupied |= std::uint64_t(1) << (int(bin) & 63);  // 4 (rounding, just below 0) is 0
  });
  // A run of 32 empty bins: the AND of 32 consecutive bits of the complement (no bin
  // occupied leaves all 64 empty).
  std::uint64_t empty = ~occupied;
  for (int s = 1; s < 32; s *= 2) empty &= detail::rotate_left(empty, s);
  return empty == 0 && within_reach;
}

}  // namespace pss
