// The cell that suits each vertex of a cloud's mesh, for its coarsening (mesh/coarsen.hpp;
// internal to src/mesh).
#pragma once

#include <algorithm>
#include <cmath>
#include <span>
#include <vector>

#include "pss/backend/cpu/parallel_for.hpp"
#include "pss/mesh/mesh_cloud.hpp"
#include "pss/spatial/support_grid.hpp"

namespace pss::mesh_detail {

// The cube's side that suits each vertex: the one asked for, or kDefaultCellPerH of the
// width of the nearest sample whose support holds it (the lattice's, the least, where none).
inline std::vector<float> vertex_cells(std::span<const vec3> positions, const SupportGrid& grid, float asked,
                                       float least) {
  std::vector<float> cell(positions.size(), asked > 0 ? asked : least);
  if (asked > 0) return cell;
  const SupportGridView view = grid.view();
  const std::span<const float> inv_h2 = grid.inv_h2();
  cpu::parallel_for(std::int64_t(cell.size()), [&](std::int64_t v) {
    const int i = view.nearest_covering(positions[std::size_t(v)]);
    if (i >= 0) cell[std::size_t(v)] = std::max(least, kDefaultCellPerH / std::sqrt(inv_h2[std::size_t(i)]));
  });
  return cell;
}

}  // namespace pss::mesh_detail
