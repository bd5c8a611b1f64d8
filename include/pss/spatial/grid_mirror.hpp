// A UniformGrid's arrays as one backend's kernels see them, and the GridView of them.
#pragma once

#include "pss/backend/mirror.hpp"
#include "pss/spatial/uniform_grid.hpp"

namespace pss {

class GridMirror {
 public:
  GridMirror(Backend backend, const UniformGrid& grid)
      : points_(backend, grid.sorted_points()), cell_start_(backend, grid.cell_start()), view_(grid.view()) {
    view_.points = points_.data();
    view_.cell_start = cell_start_.data();
  }
  const GridView& view() const { return view_; }

 private:
  Mirror<vec3> points_;
  Mirror<int> cell_start_;
  GridView view_;
};

}  // namespace pss
