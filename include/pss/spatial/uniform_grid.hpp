// Uniform grid for fixed-radius range queries: points sorted by cell (a counting sort), one
// offset per cell. Kernels see a GridView (pointers and sizes, passed by value); owners on
// the host (UniformGrid) and on the GPU (DeviceGrid) hand out views of their arrays.
#pragma once

#include <span>
#include <vector>

#include "pss/core/types.hpp"

namespace pss {

struct GridView {
  const vec3* points = nullptr;     // sorted by cell
  const int* cell_start = nullptr;  // cells + 1 offsets into points
  int count = 0;
  vec3 origin{0.0f};
  float inv_cell = 1.0f;
  ivec3 dims{1};
  // The grid's first cell on a lattice of cells from `origin` (a part of a larger grid: a
  // tile's of the whole cloud's, spatial/support_layout.hpp); cells are counted from it, so
  // a point falls in the cell it falls in on the whole lattice, rounded alike.
  ivec3 first{0};

  PSS_HOST_DEVICE ivec3 cell_of(vec3 p) const {
    const vec3 c = (p - origin) * inv_cell;
    return ivec3(clamp(int(floor(c.x)) - first.x, 0, dims.x - 1), clamp(int(floor(c.y)) - first.y, 0, dims.y - 1),
                 clamp(int(floor(c.z)) - first.z, 0, dims.z - 1));
  }

  // The cell's index in cell_start: rows along x, then y, then z.
  PSS_HOST_DEVICE int cell_index(vec3 p) const {
    const ivec3 c = cell_of(p);
    return (c.z * dims.y + c.y) * dims.x + c.x;
  }

  // Calls f(point, sorted index) for every point of the cells that the box c ± radius
  // touches: those within `radius` and some more, for callers that test without branching.
  // (Skipping rows beyond the radius and cutting rows to the ball's chord read ~30 % fewer
  // points but made no frame faster: the per-row arithmetic costs what it saves.) Cells of
  // one row are contiguous in the sorted order, so each row is one loop.
  template <class F>
  PSS_HOST_DEVICE void for_each_near(vec3 c, float radius, F&& f) const {
    const ivec3 lo = cell_of(c - vec3(radius)), hi = cell_of(c + vec3(radius));
    for (int z = lo.z; z <= hi.z; ++z) {
      for (int y = lo.y; y <= hi.y; ++y) {
        const int row = (z * dims.y + y) * dims.x;
        const int end = cell_start[row + hi.x + 1];
        for (int i = cell_start[row + lo.x]; i < end; ++i) f(points[i], i);
      }
    }
  }

  // Calls f(point, squared distance, sorted index) for every point within `radius` of c.
  template <class F>
  PSS_HOST_DEVICE void for_each_in_radius(vec3 c, float radius, F&& f) const {
    const float r2 = radius * radius;
    for_each_near(c, radius, [&](vec3 p, int i) {
      const float d2 = length2(p - c);
      if (d2 <= r2) f(p, d2, i);
    });
  }
};

// The shape of a uniform grid over `box` (the origin's cell where it is empty): cells of
// `cell_size`, grown by a quarter at a time while the box would need more than `max_cells`.
// Its points and cell_start are left unset.
GridView grid_shape(Aabb box, float cell_size, long long max_cells);

// A stable counting sort of items by key (key[i] in [0, keys)): cell_start gets keys + 1
// offsets, key k's items filling slots [cell_start[k], cell_start[k + 1]), and order[slot]
// the item in each slot. No copy of the offsets (a grid's cells may outnumber its points).
void counting_sort(std::span<const int> key, std::size_t keys, std::vector<int>& cell_start, std::vector<int>& order);

class UniformGrid {
 public:
  // Cells of `cell_size` (the query radius makes queries touch at most 3³ cells), grown
  // when the box would need more than `max_cells` cells.
  UniformGrid(std::span<const vec3> points, float cell_size, long long max_cells = 1ll << 25);

  GridView view() const;
  std::span<const vec3> sorted_points() const { return sorted_; }
  std::span<const int> cell_start() const { return cell_start_; }
  // original_index()[i] is the input index of sorted point i.
  std::span<const int> original_index() const { return original_index_; }
  ivec3 dims() const { return shape_.dims; }

 private:
  std::vector<vec3> sorted_;
  std::vector<int> cell_start_;
  std::vector<int> original_index_;
  GridView shape_;  // its origin, cells and their size
};

}  // namespace pss
