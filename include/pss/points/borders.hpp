// Where the surface of an open cloud ends (issue 26). The projection extrapolates, so without
// a bound the PSS runs on past the last samples of an open rim, a scan's border or a thin
// part's edge, a band about a ball wide (the locally refined cylinder: 10–20 % of its pixels
// extra). A point of the surface counts where its samples surround it, in its tangent plane:
// no half-plane through it is empty of N(x), i.e. it lies inside their convex hull there.
// Inside the data the samples lie on every side; beyond the last ones they all lie behind.
#pragma once

#include <cstdint>

#include "pss/core/frame.hpp"

namespace pss {

namespace detail {

// A monotone stand-in for the angle of (x, y), in [0, 4) ("diamond angle"): no atan2, and
// opposite directions lie exactly 2 apart, so that a half-plane is an interval of length 2.
PSS_INLINE float diamond_angle(float x, float y) {
  if (y >= 0) return x >= 0 ? y / (x + y) : 1 - x / (y - x);
  return x < 0 ? 2 - y / (-x - y) : 3 + x / (x - y);
}

PSS_INLINE std::uint64_t rotate_left(std::uint64_t v, int s) { return (v << s) | (v >> (64 - s)); }

}  // namespace detail

// Whether x, on the surface with `normal`, lies among the samples of `neighbours` (N(r) of a
// projection, neighbourhood.hpp): in 64 bins of direction in the tangent plane (3.6° to 7.2°
// wide), no 32 empty in a row, which would be an empty half-plane. A gap of up to 14° more
// than 180° may go unseen: x beyond a straight border by up to a tenth of ρ.
template <class Nb>
PSS_HOST_DEVICE bool samples_surround(const Nb& neighbours, vec3 x, vec3 normal) {
  const Frame frame = Frame::from_normal(x, normal);
  std::uint64_t occupied = 0;
  neighbours.for_each([&](vec3 p, float, float) {
    const vec3 l = frame.direction_to_local(p - x);
    if (l.x == 0 && l.y == 0) return;  // straight above or below x: no direction
    const int bin = int(detail::diamond_angle(l.x, l.y) * 16);
    occupied |= std::uint64_t(1) << (bin < 63 ? bin : 63);
  });
  // A run of 32 empty bins: the AND of 32 consecutive bits of the complement.
  std::uint64_t empty = ~occupied;
  for (int s = 1; s < 32; s *= 2) empty &= detail::rotate_left(empty, s);
  return occupied != 0 && empty == 0;
}

}  // namespace pss
