// A UniformGrid's arrays on the device, and the GridView of them.
#pragma once

#include "pss/backend/cuda/runtime.cuh"
#include "pss/spatial/uniform_grid.hpp"

namespace pss::cuda {

class DeviceGrid {
 public:
  explicit DeviceGrid(const GridView& host)
      : points_(std::span<const vec3>(host.points, std::size_t(host.count))),
        cell_start_(std::span<const int>(host.cell_start,
                                         std::size_t(host.dims.x) * host.dims.y * host.dims.z + 1)),
        view_(host) {
    view_.points = points_.data();
    view_.cell_start = cell_start_.data();
  }
  const GridView& view() const { return view_; }

 private:
  DeviceBuffer<vec3> points_;
  DeviceBuffer<int> cell_start_;
  GridView view_;
};

}  // namespace pss::cuda
