// The kernel that projects points onto the surface of a cloud, on either backend: what
// `pss project` runs over the input, and the normal estimate over the samples
// (sample_normals.hpp).
#pragma once

#include <cstddef>
#include <cstdint>

#include "pss/backend/backend.hpp"
#include "pss/points/surface_projection.hpp"

namespace pss {

struct ProjectedPoint {
  vec3 point;
  vec3 normal;
  ProjectionStatus status;
};

// How many points a launch of the kernel below projects where a cloud's are taken in chunks,
// each placed at once (project_cloud.cpp, sample_normals.cpp), so that the 28 bytes a point
// of the results are never all held: a GPU is given enough threads a launch to fill it.
inline std::size_t projection_chunk(Backend backend) { return std::size_t(1) << (backend == Backend::cpu ? 16 : 20); }

// The per-point kernel both backends run.
PSS_INLINE ProjectedPoint project_point(const SupportGridView& grid, vec3 r, vec3 hint, const ProjectionParams& params) {
  const Projection p = project_onto_surface(grid, r, params, hint);
  const bool projected = p.status == ProjectionStatus::converged || p.status == ProjectionStatus::not_converged;
  return {p.point, projected ? reported_normal(grid, p.point, p.normal, params) : p.normal, p.status};
}

// out[i] = the projection of points[i] (backend/parallel_for.hpp).
struct ProjectPointsKernel {
  SupportGridView grid;
  const vec3* points;
  const vec3* hints;  // the file's normals; null for none
  ProjectedPoint* out;
  ProjectionParams params;
  PSS_HOST_DEVICE void operator()(std::int64_t i) const {
    out[i] = project_point(grid, points[i], hints ? hints[i] : vec3(0.0f), params);
  }
};

}  // namespace pss
