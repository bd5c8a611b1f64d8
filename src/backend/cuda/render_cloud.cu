#include "device_grid.cuh"
#include "render_frame.cuh"
#include "pss/points/render_cloud.hpp"

namespace pss::cuda {

void fit_local_polynomials(const GridView& grid, std::span<const vec3> points, std::span<const vec3> hints, float h,
                           float rho, std::span<LocalFit> out, Progress* progress) {
  for_each_point("local polynomials", grid, points, hints, out, progress,
                 [=] __device__(const GridView& g, vec3 p, vec3 hint) { return fit_local_polynomial(g, p, hint, h, rho); });
}

RenderedFrame render_points(const PointSurfaceView& surface, const Camera& camera, const TraceSettings& settings,
                    Stats& stats) {
  const DeviceGrid grid(surface.grid);
  const DeviceBuffer<BvhNode> nodes(std::span<const BvhNode>(surface.bvh.nodes, std::size_t(surface.bvh.node_count)));
  const DeviceBuffer<int> primitives(
      std::span<const int>(surface.bvh.primitives, std::size_t(surface.bvh.primitive_count)));
  const DeviceBuffer<LocalPolynomial> locals(
      std::span<const LocalPolynomial>(surface.locals, std::size_t(surface.bvh.primitive_count)));
  PointSurfaceView device = surface;
  device.grid = grid.view();
  device.bvh.nodes = nodes.data();
  device.bvh.primitives = primitives.data();
  device.locals = locals.data();
  return render_frame_device(PointFinder{device}, camera, settings, stats);
}

}  // namespace pss::cuda
