#include "pss/spatial/support_grid.hpp"

#include <algorithm>
#include <cmath>

#include "pss/core/error.hpp"

namespace pss {

SupportGrid::SupportGrid(std::span<const vec3> points, std::span<const float> h, float kappa, long long max_cells) {
  if (h.size() != points.size()) throw Error("support grid: one width per point is needed");
  if (!(kappa > 0) || !std::isfinite(kappa)) throw Error("support grid: rho/h must be a positive number");
  float least = kInfinity;
  for (float w : h) {
    if (!(w > 0) || !std::isfinite(w)) throw Error("support grid: every width h must be a positive number");
    least = std::min(least, w);
  }
  // Level l holds widths in [2^l, 2^(l+1))·least; the last level takes every wider one.
  constexpr int L = SupportGridView::kMaxLevels;
  auto level_of = [&](float w) { return std::clamp(int(std::floor(std::log2(double(w) / double(least)))), 0, L - 1); };
  std::vector<std::vector<int>> members(L);
  for (std::size_t i = 0; i < points.size(); ++i) members[std::size_t(level_of(h[i]))].push_back(int(i));

  kappa_ = kappa;
  sorted_.reserve(points.size());
  inv_h2_.reserve(points.size());
  original_index_.reserve(points.size());
  for (int l = 0; l < L; ++l) {
    const std::vector<int>& m = members[std::size_t(l)];
    if (m.empty() && !(points.empty() && l == 0)) continue;  // an empty cloud keeps one empty level
    std::vector<vec3> p(m.size());
    float widest = 0;
    for (std::size_t j = 0; j < m.size(); ++j) {
      p[j] = points[std::size_t(m[j])];
      widest = std::max(widest, h[std::size_t(m[j])]);
    }
    const float radius = widest > 0 ? kappa * widest : 1.0f;
    // Far more cells than samples is memory for nothing: a level of few wide samples (the
    // sparse part of a cloud, a box stretched by a stray point) gets cells to match.
    const long long cells = std::min(std::max<long long>(32 * (long long)m.size(), 4096), max_cells);
    const UniformGrid grid(p, 0.5f * radius, cells);
    const int first = int(sorted_.size());
    const GridView level = grid.view();
    level_offset_.push_back(int(cell_start_.size()));
    for (int start : grid.cell_start()) cell_start_.push_back(first + start);
    for (std::size_t s = 0; s < m.size(); ++s) {
      const int i = m[std::size_t(grid.original_index()[s])];
      sorted_.push_back(grid.sorted_points()[s]);
      inv_h2_.push_back(1.0f / (h[std::size_t(i)] * h[std::size_t(i)]));
      original_index_.push_back(i);
    }
    levels_.push_back({level, radius});
  }
  // The levels' pointers, once the arrays have their final size.
  for (std::size_t l = 0; l < levels_.size(); ++l) {
    levels_[l].grid.points = sorted_.data();
    levels_[l].grid.cell_start = cell_start_.data() + level_offset_[l];
    levels_[l].grid.count = int(sorted_.size());
  }
}

SupportGridView SupportGrid::view() const {
  SupportGridView v;
  v.points = sorted_.data();
  v.inv_h2 = inv_h2_.data();
  v.normals = normals_.empty() ? nullptr : normals_.data();
  v.level = levels_.data();
  v.levels = int(levels_.size());
  v.count = int(sorted_.size());
  v.kappa2 = kappa_ * kappa_;
  return v;
}

void SupportGrid::set_normals(std::vector<vec3> sorted_normals) {
  if (sorted_normals.size() != sorted_.size()) throw Error("SupportGrid::set_normals: one normal per sample");
  normals_ = std::move(sorted_normals);
}

void SupportGrid::renumber(std::span<const int> input_index) {
  for (int& i : original_index_) i = input_index[std::size_t(i)];
}

}  // namespace pss
