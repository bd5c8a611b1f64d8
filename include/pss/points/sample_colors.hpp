// The samples' own colours on the surface (`pss render --color`): at a point x, the mean of
// the colours of N(x) weighted by θ3(‖pᵢ − x‖), the weights with which the projection
// (paper §3) builds the surface there. The paper has no colour; this is the same
// neighbourhood and weights carried over (docs/paper-notes.md).
#pragma once

#include "pss/fit/weights.hpp"
#include "pss/spatial/support_grid.hpp"

namespace pss {

// colors[i] is sorted sample i's colour in linear RGB (sums of light, not of sRGB codes).
// `fallback` where no sample's support holds x.
PSS_INLINE vec3 interpolated_color(const SupportGridView& grid, const vec3* colors, vec3 x, vec3 fallback) {
  vec3 sum(0.0f);
  float weight_sum = 0;
  grid.for_each_covering(x, [&](vec3, float d2, int i) {
    const float w = grid.mass_of(i) * gaussian_weight(d2, grid.inv_h2[i]);
    sum += w * colors[i];
    weight_sum += w;
  });
  return weight_sum > 0 ? sum / weight_sum : fallback;
}

}  // namespace pss
