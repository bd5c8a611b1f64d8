// Ray tracing the PSS of a point cloud (paper §5.2), what `pss render` does: the
// preprocessing (grid, per-sample polynomials), the BVH over the balls, and a frame from
// the shared render pipeline, on the CPU or the GPU.
#pragma once

#include <span>
#include <vector>

#include "pss/backend/backend.hpp"
#include "pss/points/cloud.hpp"
#include "pss/points/ray_pss.hpp"
#include "pss/render/rendered_frame.hpp"

namespace pss {

// The surface finder of a point cloud for the render pipeline (render/trace.hpp).
struct PointFinder {
  PointSurfaceView surface;

  PSS_HOST_DEVICE Hit primary(const Ray& ray) const {
    return intersect_pss(surface, ray, 0.0f, kInfinity, surface.params.max_iterations);
  }
  PSS_HOST_DEVICE Hit secondary(const Ray& ray, float t_max) const {
    return intersect_secondary(surface, ray, t_max, surface.params.max_iterations);
  }
  PSS_HOST_DEVICE float secondary_offset() const { return surface.params.secondary_offset; }
};

// The host owner of everything a PointSurfaceView points to.
class PreparedCloud {
 public:
  // Runs the "Initial approximation" on `backend` and builds the BVH (on the host); the
  // phases "preprocess" and "acceleration structure" go to stats.
  PreparedCloud(const PointCloud& cloud, const RayPssParams& params, Backend backend, Stats& stats);
  PreparedCloud(const PreparedCloud&) = delete;
  PreparedCloud& operator=(const PreparedCloud&) = delete;

  PointSurfaceView view() const;
  std::span<const LocalPolynomial> locals() const { return locals_; }  // BVH order
  std::int64_t left_out() const { return left_out_; }  // samples with < 3 neighbours
  const Bvh& bvh() const { return bvh_; }

 private:
  RayPssParams params_;
  UniformGrid grid_;
  std::vector<LocalPolynomial> locals_;
  std::int64_t left_out_ = 0;
  Bvh bvh_;
};

// Throws Error for parameters that are not positive and finite.
void validate(const RayPssParams& params);

RenderedFrame render_cloud(const PreparedCloud& cloud, const Camera& camera, const TraceSettings& settings, Backend backend,
                   Stats& stats);

namespace cuda {
// fit_local_polynomial for every point, on the GPU; `grid` is a host view that is uploaded.
void fit_local_polynomials(const GridView& grid, std::span<const vec3> points, std::span<const vec3> hints, float h,
                           float rho, std::span<LocalFit> out, Progress* progress);
// The frame on the GPU: the view's arrays (host pointers) are uploaded, the same kernels run.
RenderedFrame render_points(const PointSurfaceView& surface, const Camera& camera, const TraceSettings& settings,
                    Stats& stats);
}  // namespace cuda

}  // namespace pss
