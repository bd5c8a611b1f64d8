// A SupportGrid's arrays as one backend's kernels see them, and the SupportGridView of them.
#pragma once

#include <vector>

#include "pss/backend/mirror.hpp"
#include "pss/spatial/support_grid.hpp"

namespace pss {

class GridMirror {
 public:
  GridMirror(Backend backend, const SupportGrid& grid)
      : points_(backend, grid.sorted_points()),
        inv_h2_(backend, grid.inv_h2()),
        normals_(backend, grid.normals()),
        mass_(backend, grid.masses()),
        cell_start_(backend, grid.cell_starts()),
        pointed_(levels_pointing_to(grid, points_.data(), cell_start_.data())),
        levels_(backend, pointed_),
        view_(grid.view()) {
    view_.points = points_.data();
    view_.inv_h2 = inv_h2_.data();
    view_.normals = grid.normals().empty() ? nullptr : normals_.data();
    view_.mass = grid.masses().empty() ? nullptr : mass_.data();
    view_.level = levels_.data();
  }
  const SupportGridView& view() const { return view_; }

 private:
  // The grid's levels with their pointers into this backend's copies of the arrays.
  static std::vector<SupportLevel> levels_pointing_to(const SupportGrid& grid, const vec3* points,
                                                      const int* cell_start) {
    std::vector<SupportLevel> levels(grid.levels_on_host().begin(), grid.levels_on_host().end());
    for (std::size_t l = 0; l < levels.size(); ++l) {
      levels[l].grid.points = points;
      levels[l].grid.cell_start = cell_start + grid.level_cell_offset()[l];
    }
    return levels;
  }

  Mirror<vec3> points_;
  Mirror<float> inv_h2_;
  Mirror<vec3> normals_;
  Mirror<float> mass_;
  Mirror<int> cell_start_;
  std::vector<SupportLevel> pointed_;  // what levels_ mirrors (on the CPU, is)
  Mirror<SupportLevel> levels_;
  SupportGridView view_;
};

}  // namespace pss
