// The ρ-neighbourhood N(r) of a point with its Gaussian weights θ3(‖pᵢ − r‖), gathered
// once: every sum of one projection runs over the same samples (Eq. 1, 2 and the
// polynomial), so later passes need no grid walk, and those weighted from r no exp().
// A fixed-size buffer (no allocation, usable in kernels); a neighbourhood larger than it
// is read from the grid again, with the same result.
#pragma once

#include "pss/fit/weights.hpp"
#include "pss/spatial/uniform_grid.hpp"

namespace pss {

template <int Capacity>
struct NeighbourhoodOf {
  static constexpr int kCapacity = Capacity;

  const GridView* grid;
  vec3 center;
  float rho, h;
  int count = 0;
  vec3 point[Capacity > 0 ? Capacity : 1];
  float weight[Capacity > 0 ? Capacity : 1];

  // Gathers N(center) and calls first(p, w) for each sample as it goes.
  template <class F>
  PSS_HOST_DEVICE NeighbourhoodOf(const GridView& g, vec3 c, float radius, float width, F&& first)
      : grid(&g), center(c), rho(radius), h(width) {
    grid->for_each_in_radius(center, rho, [&](vec3 p, float d2, int) {
      const float w = gaussian_weight(d2, h);
      if (count < Capacity) {
        point[count] = p;
        weight[count] = w;
      }
      ++count;
      first(p, w);
    });
  }

  // f(p, w) for every sample again, in the same order.
  template <class F>
  PSS_HOST_DEVICE void for_each(F&& f) const {
    if (count <= Capacity) {
      for (int i = 0; i < count; ++i) f(point[i], weight[i]);
    } else {
      grid->for_each_in_radius(center, rho, [&](vec3 p, float d2, int) { f(p, gaussian_weight(d2, h)); });
    }
  }
};

// ρ = 2h around the default h holds ~60 samples (points/spacing.hpp); 128 covers uneven
// sampling without spilling in most places. On the GPU too: walking the grid again at each
// pass (PSS_DEVICE_NEIGHBOURS=0, 128–880 bytes of stack instead of 2.2–2.8 KB) measured
// 9 % slower frames and half the projection rate on an H100 (docs/benchmarks.md).
#ifndef PSS_DEVICE_NEIGHBOURS
#define PSS_DEVICE_NEIGHBOURS 128
#endif
#if defined(__CUDA_ARCH__)
using Neighbourhood = NeighbourhoodOf<PSS_DEVICE_NEIGHBOURS>;
#else
using Neighbourhood = NeighbourhoodOf<128>;
#endif

}  // namespace pss
