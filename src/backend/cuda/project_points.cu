#include "device_grid.cuh"
#include "pss/points/project_cloud.hpp"

namespace pss::cuda {

void project_points(const GridView& grid, std::span<const vec3> queries, std::span<const vec3> hints,
                    const ProjectionParams& params, std::span<ProjectedPoint> out, Progress* progress) {
  for_each_point("projection", grid, queries, hints, out, progress,
                 [=] __device__(const GridView& g, vec3 r, vec3 hint) { return project_point(g, r, hint, params); });
}

}  // namespace pss::cuda
