#include "pss/spatial/support_layout.hpp"

#include <algorithm>
#include <cmath>

namespace pss {

int support_level(float w, float least) {
  return std::clamp(int(std::floor(std::log2(double(w) / double(least)))), 0, kSupportLevels - 1);
}

void SupportTally::add(vec3 p, float w) {
  const int l = support_level(w, least);
  box[std::size_t(l)].grow(p);
  widest[std::size_t(l)] = std::max(widest[std::size_t(l)], w);
  ++members[std::size_t(l)];
}

void SupportTally::add(const SupportTally& other) {
  for (std::size_t l = 0; l < kSupportLevels; ++l) {
    if (other.members[l] == 0) continue;
    box[l].grow(other.box[l]);
    widest[l] = std::max(widest[l], other.widest[l]);
    members[l] += other.members[l];
  }
}

SupportLayout support_layout(const SupportTally& tally, float kappa, long long max_cells) {
  SupportLayout layout;
  layout.least = tally.least;
  layout.kappa = kappa;
  long long samples = 0;
  for (const long long m : tally.members) samples += m;
  for (std::size_t l = 0; l < kSupportLevels; ++l) {
    if (tally.members[l] == 0 && !(samples == 0 && l == 0)) continue;  // an empty cloud keeps one empty level
    const float radius = tally.widest[l] > 0 ? kappa * tally.widest[l] : 1.0f;
    // Far more cells than samples is memory for nothing: a level of few wide samples (the
    // sparse part of a cloud, a box stretched by a stray point) gets cells to match.
    layout.shape[l] = grid_shape(tally.box[l], 0.5f * radius, std::min(std::max(32 * tally.members[l], 4096ll), max_cells));
    layout.radius[l] = radius;
  }
  return layout;
}

}  // namespace pss
