#include "pss/spatial/uniform_grid.hpp"

#include <algorithm>
#include <cmath>

#include "pss/core/error.hpp"

namespace pss {

GridView grid_shape(Aabb box, float cell_size, long long max_cells) {
  if (!(cell_size > 0) || !std::isfinite(cell_size)) throw Error("grid cell size must be positive");
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
  GridView shape;
  shape.origin = box.lo;
  shape.inv_cell = 1.0f / cell_size;
  shape.dims = ivec3(int(cells_along(extent.x, cell_size)), int(cells_along(extent.y, cell_size)),
                     int(cells_along(extent.z, cell_size)));
  return shape;
}

void counting_sort(std::span<const int> key, std::size_t keys, std::vector<int>& cell_start, std::vector<int>& order) {
  cell_start.assign(keys + 1, 0);
  for (int k : key) ++cell_start[std::size_t(k) + 1];
  for (std::size_t k = 0; k < keys; ++k) cell_start[k + 1] += cell_start[k];
  // Each item to its key's next free slot, which moves cell_start[k] to key k's end, that is
  // key k + 1's start: shifted back by one, the offsets are the starts again.
  order.resize(key.size());
  for (std::size_t i = 0; i < key.size(); ++i) order[std::size_t(cell_start[std::size_t(key[i])]++)] = int(i);
  for (std::size_t k = keys; k > 0; --k) cell_start[k] = cell_start[k - 1];
  cell_start[0] = 0;
}

UniformGrid::UniformGrid(std::span<const vec3> points, float cell_size, long long max_cells) {
  Aabb box;
  for (const vec3& p : points) box.grow(p);
  shape_ = grid_shape(box, cell_size, max_cells);
  std::vector<int> cell(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) cell[i] = shape_.cell_index(points[i]);
  const ivec3 d = shape_.dims;
  counting_sort(cell, std::size_t(d.x) * d.y * d.z, cell_start_, original_index_);
  sorted_.resize(points.size());
  for (std::size_t s = 0; s < sorted_.size(); ++s) sorted_[s] = points[std::size_t(original_index_[s])];
}

GridView UniformGrid::view() const {
  GridView v = shape_;
  v.points = sorted_.data();
  v.cell_start = cell_start_.data();
  v.count = int(sorted_.size());
  return v;
}

}  // namespace pss
