// The cells of a SupportGrid's levels (spatial/support_grid.hpp), decided by its samples'
// widths and places alone: the least width (which sets each sample's level), and each
// level's box, widest width and count. All are minima, maxima and counts, the same in any
// order, so tiles that tally their own samples and add the tallies up get the whole cloud's
// layout; a tile's grid built on it has the whole cloud's cells (a part of each level's
// lattice), and every query walks the same samples in the same order as in core, so that
// every sum rounds alike (issue 28: tiles to the last bit).
#pragma once

#include <array>
#include <span>

#include "pss/spatial/uniform_grid.hpp"

namespace pss {

inline constexpr int kSupportLevels = 8;  // SupportGridView::kMaxLevels

// A sample of width w lies on level floor(log2(w / least)), the last taking every wider one.
int support_level(float w, float least);

// What decides the layout, tallied over samples once their least width is known.
struct SupportTally {
  float least = 0;
  std::array<Aabb, kSupportLevels> box{};
  std::array<float, kSupportLevels> widest{};
  std::array<long long, kSupportLevels> members{};

  void add(vec3 p, float w);
  void add(const SupportTally& other);  // of the same least
};

struct SupportLayout {
  float least = 0, kappa = 2;
  // Each level's lattice (origin, cell, dims; no points), and its largest ρ_i; a level of no
  // samples has radius 0.
  std::array<GridView, kSupportLevels> shape{};
  std::array<float, kSupportLevels> radius{};
};

// The layout of the tallied samples: each level's cells half its largest ρ_i, at most 32
// per sample (4,096 at least) and at most max_cells. An empty tally makes one empty level.
SupportLayout support_layout(const SupportTally& tally, float kappa, long long max_cells = 1ll << 25);

}  // namespace pss
