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

// out[i] = kernel(grid, points[i], hints[i]) on the device: the per-sample pattern of the
// projection and of the local polynomials. `kernel` is a __device__ lambda.
template <class Out, class Kernel>
void for_each_point(const char* name, const GridView& grid, std::span<const vec3> points, std::span<const vec3> hints,
                    std::span<Out> out, Progress* progress, Kernel kernel) {
  const DeviceGrid device_grid(grid);
  const DeviceBuffer<vec3> d_points(points);
  const DeviceBuffer<vec3> d_hints(hints);
  DeviceBuffer<Out> d_out(out.size());
  const GridView g = device_grid.view();
  const vec3* p = d_points.data();
  const vec3* n = d_hints.data();
  Out* o = d_out.data();
  parallel_for(name, std::int64_t(points.size()), [=] __device__(std::int64_t i) { o[i] = kernel(g, p[i], n[i]); },
               progress);
  d_out.download(out);
}

}  // namespace pss::cuda
