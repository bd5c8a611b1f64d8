#include "pss/spatial/support_grid.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "pss/core/error.hpp"
#include "pss/core/memory.hpp"

namespace pss {

namespace {

void check_widths(std::span<const vec3> points, std::span<const float> h, float kappa) {
  if (h.size() != points.size()) throw Error("support grid: one width per point is needed");
  if (!(kappa > 0) || !std::isfinite(kappa)) throw Error("support grid: rho/h must be a positive number");
}

}  // namespace

SupportGrid::SupportGrid(std::span<const vec3> points, std::span<const float> h, float kappa, long long max_cells) {
  check_widths(points, h, kappa);
  const auto index = [](std::size_t i) { return i; };
  build(points, h, points.size(), index, support_layout(tally(points, h, points.size(), index), kappa, max_cells), false);
}

SupportGrid::SupportGrid(std::span<const vec3> points, std::span<const float> h, std::span<const int> subset,
                         float kappa, long long max_cells) {
  check_widths(points, h, kappa);
  check_subset(points, subset);
  const auto index = [&](std::size_t s) { return std::size_t(subset[s]); };
  build(points, h, subset.size(), index, support_layout(tally(points, h, subset.size(), index), kappa, max_cells), false);
}

SupportGrid::SupportGrid(std::span<const vec3> points, std::span<const float> h, std::span<const int> subset,
                         const SupportLayout& layout) {
  check_widths(points, h, layout.kappa);
  check_subset(points, subset);
  for (const int i : subset)
    if (!(h[std::size_t(i)] >= layout.least) || !std::isfinite(h[std::size_t(i)]))
      throw Error("support grid: a width lies outside the layout's");
  build(points, h, subset.size(), [&](std::size_t s) { return std::size_t(subset[s]); }, layout, true);
}

void SupportGrid::check_subset(std::span<const vec3> points, std::span<const int> subset) {
  for (int i : subset)
    if (i < 0 || std::size_t(i) >= points.size()) throw Error("support grid: a subset index is out of range");
}

template <class Index>
SupportTally SupportGrid::tally(std::span<const vec3> points, std::span<const float> h, std::size_t count, Index index) {
  SupportTally t;
  t.least = kInfinity;
  for (std::size_t s = 0; s < count; ++s) {
    const float w = h[index(s)];
    if (!(w > 0) || !std::isfinite(w)) throw Error("support grid: every width h must be a positive number");
    t.least = std::min(t.least, w);
  }
  for (std::size_t s = 0; s < count; ++s) t.add(points[index(s)], h[index(s)]);
  return t;
}

template <class Index>
void SupportGrid::build(std::span<const vec3> points, std::span<const float> h, std::size_t count, Index index,
                        const SupportLayout& layout, bool part) {
  // Each level's cells: the layout's lattice whole, or where `part`, the part of it that
  // the samples here occupy (a tile's grid of the whole cloud's cells).
  kappa_ = layout.kappa;
  std::array<int, kSupportLevels> level_at{};  // the level's index in levels_; -1 for an empty one
  std::array<ivec3, kSupportLevels> lo, hi;
  lo.fill(ivec3(std::numeric_limits<int>::max()));
  hi.fill(ivec3(std::numeric_limits<int>::min()));
  std::vector<unsigned char> level(count);
  for (std::size_t s = 0; s < count; ++s) {
    const std::size_t i = index(s);
    const int l = support_level(h[i], layout.least);
    level[s] = (unsigned char)l;
    if (!part) continue;
    if (!(layout.radius[std::size_t(l)] > 0)) throw Error("support grid: a sample on a level the layout has not");
    const ivec3 c = layout.shape[std::size_t(l)].cell_of(points[i]);
    lo[std::size_t(l)] = glm::min(lo[std::size_t(l)], c);
    hi[std::size_t(l)] = glm::max(hi[std::size_t(l)], c);
  }
  std::size_t cells = 0;
  for (std::size_t l = 0; l < kSupportLevels; ++l) {
    level_at[l] = -1;
    if (!(layout.radius[l] > 0)) continue;
    GridView shape = layout.shape[l];
    if (part) {
      if (lo[l].x > hi[l].x) continue;  // no sample of the set on this level
      shape.first = lo[l];
      shape.dims = hi[l] - lo[l] + 1;
    }
    level_at[l] = int(levels_.size());
    levels_.push_back({shape, layout.radius[l]});
    level_offset_.push_back(int(cells));
    cells += std::size_t(shape.dims.x) * shape.dims.y * shape.dims.z;
  }
  if (levels_.empty()) {  // a set of no samples: one empty level
    levels_.push_back({layout.shape[0], 1.0f});
    level_offset_.push_back(0);
    cells = 1;
    levels_[0].grid.dims = ivec3(1);
  }
  if (cells >= std::size_t(std::numeric_limits<int>::max())) throw Error("support grid: too many cells");
  {
    std::vector<int> key(count);
    for (std::size_t s = 0; s < count; ++s) {
      const int at = level_at[level[s]];
      key[s] = level_offset_[std::size_t(at)] + levels_[std::size_t(at)].grid.cell_index(points[index(s)]);
    }
    release(level);
    counting_sort(key, cells, cell_start_, original_index_);
  }
  for (int& s : original_index_) s = int(index(std::size_t(s)));
  sorted_.resize(count);
  inv_h2_.resize(count);
  for (std::size_t s = 0; s < count; ++s) {
    const auto i = std::size_t(original_index_[s]);
    sorted_[s] = points[i];
    inv_h2_[s] = 1.0f / (h[i] * h[i]);
  }
  // The levels' pointers, once the arrays have their final size.
  for (std::size_t l = 0; l < levels_.size(); ++l) {
    levels_[l].grid.points = sorted_.data();
    levels_[l].grid.cell_start = cell_start_.data() + level_offset_[l];
    levels_[l].grid.count = int(sorted_.size());
  }
}

std::vector<int> SupportGrid::cell_order(std::span<const vec3> points) const {
  const GridView& cells = levels_.front().grid;
  std::vector<int> key(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) key[i] = cells.cell_index(points[i]);
  std::vector<int> start, order;
  counting_sort(key, std::size_t(cells.dims.x) * cells.dims.y * cells.dims.z, start, order);
  return order;
}

SupportGridView SupportGrid::view() const {
  SupportGridView v;
  v.points = sorted_.data();
  v.inv_h2 = inv_h2_.data();
  v.normals = normals_.empty() ? nullptr : normals_.data();
  v.mass = mass_.empty() ? nullptr : mass_.data();
  v.level = levels_.data();
  v.levels = int(levels_.size());
  v.count = int(sorted_.size());
  v.kappa2 = kappa_ * kappa_;
  return v;
}

void SupportGrid::set_members(std::span<const int> into) {
  mass_.clear();
  member_start_.clear();
  member_.clear();
  if (into.empty()) return;
  const std::size_t m = sorted_.size();
  std::vector<int> sorted_of(into.size(), -1);  // each sample's place in sorted order
  for (std::size_t k = 0; k < m; ++k) sorted_of[std::size_t(original_index_[k])] = int(k);
  member_start_.assign(m + 1, 0);
  for (const int rep : into) {
    const int k = sorted_of[std::size_t(rep)];
    if (k >= 0) ++member_start_[std::size_t(k) + 1];
  }
  for (std::size_t k = 0; k < m; ++k) member_start_[k + 1] += member_start_[k];
  member_.resize(std::size_t(member_start_[m]));
  std::vector<int> next(member_start_.begin(), member_start_.end() - 1);
  for (std::size_t i = 0; i < into.size(); ++i) {
    const int k = sorted_of[std::size_t(into[i])];
    if (k >= 0) member_[std::size_t(next[std::size_t(k)]++)] = int(i);
  }
  mass_.resize(m);
  for (std::size_t k = 0; k < m; ++k) mass_[k] = float(member_start_[k + 1] - member_start_[k]);
}

void SupportGrid::set_normals(std::vector<vec3> sorted_normals) {
  if (sorted_normals.size() != sorted_.size()) throw Error("SupportGrid::set_normals: one normal per sample");
  normals_ = std::move(sorted_normals);
}

}  // namespace pss
