// The samples' own colours on the surface (`pss render --color`): at a point x, the mean of
// the colours of N(x) weighted by θ3(‖pᵢ − x‖), the weights with which the projection
// (paper §3) builds the surface there. The paper has no colour; this is the same
// neighbourhood and weights carried over (docs/paper-notes.md).
#pragma once

#include "pss/fit/weights.hpp"
#include "pss/spatial/uniform_grid.hpp"

namespace pss {

// colors[i] is sorted sample i's colour in linear RGB (sums of light, not of sRGB codes).
// `fallback` where no sample lies within ρ of x.
PSS_INLINE vec3 interpolated_color(const GridView& grid, const vec3* colors, vec3 x, float rho, float h,
                                   vec3 fallback) {
  vec3 sum(0.0f);
  float weight_sum = 0;
  grid.for_each_in_radius(x, rho, [&](vec3, float d2, int i) {
    const float w = gaussian_weight(d2, h);
    sum += w * colors[i];
    weight_sum += w;
  });
  return weight_sum > 0 ? sum / weight_sum : fallback;
}

}  // namespace pss
