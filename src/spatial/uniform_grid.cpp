#include "pss/spatial/uniform_grid.hpp"

#include <cmath>

#include "pss/core/error.hpp"

namespace pss {

UniformGrid::UniformGrid(std::span<const vec3> points, float cell_size, long long max_cells) {
  if (!(cell_size > 0) || !std::isfinite(cell_size)) throw Error("grid cell size must be positive");
  Aabb box;
  for (const vec3& p : points) box.grow(p);
  if (box.empty()) box.grow(vec3(0.0f));
  const vec3 extent = box.extent();
  // In double: a cell far smaller than the box (h = 1e-8 on a cloud of size 1) makes a count
  // beyond long long, whose overflow once passed the test below and sized the grid from garbage.
  auto cells_along = [&](float e, float size) { return std::max(1.0, std::floor(double(e) / double(size)) + 1); };
  for (;;) {
    const double total = cells_along(extent.x, cell_size) * cells_along(extent.y, cell_size) *
                         cells_along(extent.z, cell_size);
    if (total <= double(max_cells)) break;
    cell_size *= 1.25f;
  }
  cell_size_ = cell_size;
  origin_ = box.lo;
  dims_ = ivec3(int(cells_along(extent.x, cell_size)), int(cells_along(extent.y, cell_size)),
                int(cells_along(extent.z, cell_size)));

  GridView shape;
  shape.origin = origin_;
  shape.inv_cell = 1.0f / cell_size_;
  shape.dims = dims_;
  const std::size_t cells = std::size_t(dims_.x) * dims_.y * dims_.z;
  std::vector<int> cell_of_point(points.size());
  cell_start_.assign(cells + 1, 0);
  for (std::size_t i = 0; i < points.size(); ++i) {
    const ivec3 c = shape.cell_of(points[i]);
    cell_of_point[i] = (c.z * dims_.y + c.y) * dims_.x + c.x;
    ++cell_start_[cell_of_point[i] + 1];
  }
  for (std::size_t c = 0; c < cells; ++c) cell_start_[c + 1] += cell_start_[c];
  std::vector<int> next(cell_start_.begin(), cell_start_.end() - 1);
  sorted_.resize(points.size());
  original_index_.resize(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    const int slot = next[cell_of_point[i]]++;
    sorted_[slot] = points[i];
    original_index_[slot] = int(i);
  }
}

GridView UniformGrid::view() const {
  GridView v;
  v.points = sorted_.data();
  v.cell_start = cell_start_.data();
  v.count = int(sorted_.size());
  v.origin = origin_;
  v.inv_cell = 1.0f / cell_size_;
  v.dims = dims_;
  return v;
}

}  // namespace pss
