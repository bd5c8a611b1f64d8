#include "device_grid.cuh"
#include "pss/points/project_cloud.hpp"

namespace pss::cuda {

void project_points(const GridView& grid, std::span<const vec3> queries, std::span<const vec3> hints,
                    const ProjectionParams& params, std::span<ProjectedPoint> out, Progress* progress) {
  const DeviceGrid device_grid(grid);
  const DeviceBuffer<vec3> d_queries(queries);
  const DeviceBuffer<vec3> d_hints(hints);
  DeviceBuffer<ProjectedPoint> d_out(out.size());
  const GridView g = device_grid.view();
  const vec3* q = d_queries.data();
  const vec3* h = d_hints.data();
  ProjectedPoint* o = d_out.data();
  parallel_for("projection", std::int64_t(queries.size()),
               [=] __device__(std::int64_t i) { o[i] = project_point(g, q[i], h[i], params); }, progress);
  d_out.download(out);
}

}  // namespace pss::cuda
