#include "pss/spatial/support_grid.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "pss/core/error.hpp"
#include "pss/core/memory.hpp"

namespace pss {

SupportGrid::SupportGrid(std::span<const vec3> points, std::span<const float> h, float kappa, long long max_cells) {
  build(points, h, points.size(), [](std::size_t i) { return i; }, kappa, max_cells);
}

SupportGrid::SupportGrid(std::span<const vec3> points, std::span<const float> h, std::span<const int> subset,
                         float kappa, long long max_cells) {
  for (int i : subset)
    if (i < 0 || std::size_t(i) >= points.size()) throw Error("support grid: a subset index is out of range");
  build(points, h, subset.size(), [&](std::size_t s) { return std::size_t(subset[s]); }, kappa, max_cells);
}

template <class Index>
void SupportGrid::build(std::span<const vec3> points, std::span<const float> h, std::size_t count, Index index,
                        float kappa, long long max_cells) {
  if (h.size() != points.size()) throw Error("support grid: one width per point is needed");
  if (!(kappa > 0) || !std::isfinite(kappa)) throw Error("support grid: rho/h must be a positive number");
  float least = kInfinity;
  for (std::size_t s = 0; s < count; ++s) {
    const float w = h[index(s)];
    if (!(w > 0) || !std::isfinite(w)) throw Error("support grid: every width h must be a positive number");
    least = std::min(least, w);
  }
  // Level l holds widths in [2^l, 2^(l+1))·least; the last level takes every wider one.
  constexpr int L = SupportGridView::kMaxLevels;
  auto level_of = [&](float w) { return std::clamp(int(std::floor(std::log2(double(w) / double(least)))), 0, L - 1); };
  std::vector<unsigned char> level(count);
  std::array<Aabb, L> box;
  std::array<float, L> widest{};
  std::array<long long, L> members{};
  for (std::size_t s = 0; s < count; ++s) {
    const std::size_t i = index(s);
    const int l = level_of(h[i]);
    level[s] = (unsigned char)l;
    box[l].grow(points[i]);
    widest[l] = std::max(widest[l], h[i]);
    ++members[l];
  }
  // Each level a uniform grid; one counting sort over every level's cells, one after another,
  // sorts the samples by level, then by cell, then by their order here.
  kappa_ = kappa;
  std::array<int, L> level_at{};  // the level's index in levels_; -1 for an empty one
  std::size_t cells = 0;
  for (int l = 0; l < L; ++l) {
    level_at[l] = -1;
    if (members[l] == 0 && !(count == 0 && l == 0)) continue;  // an empty cloud keeps one empty level
    const float radius = widest[l] > 0 ? kappa * widest[l] : 1.0f;
    // Far more cells than samples is memory for nothing: a level of few wide samples (the
    // sparse part of a cloud, a box stretched by a stray point) gets cells to match.
    const GridView shape = grid_shape(box[l], 0.5f * radius, std::min(std::max(32 * members[l], 4096ll), max_cells));
    level_at[l] = int(levels_.size());
    levels_.push_back({shape, radius});
    level_offset_.push_back(int(cells));
    cells += std::size_t(shape.dims.x) * shape.dims.y * shape.dims.z;
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
