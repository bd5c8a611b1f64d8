// Ray tracing the PSS of a point cloud (paper §5.2), what `pss render` does: the
// preprocessing (grid, per-sample polynomials), the BVH over the balls, and a frame from
// the shared render pipeline, on the CPU or the GPU.
#pragma once

#include <memory>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include "pss/backend/backend.hpp"
#include "pss/core/stats.hpp"
#include "pss/points/border_choice.hpp"
#include "pss/points/cloud.hpp"
#include "pss/points/ray_pss.hpp"
#include "pss/points/outliers.hpp"
#include "pss/points/sample_colors.hpp"
#include "pss/points/sample_normals.hpp"
#include "pss/points/support.hpp"
#include "pss/render/rendered_frame.hpp"

namespace pss {

// The surface finder of a point cloud for the render pipeline (render/trace.hpp).
struct PointFinder {
  static constexpr bool kTiledRays = false;  // frame_kernels.hpp: rows measured faster for clouds
  PointSurfaceView surface;

  PSS_HOST_DEVICE Hit primary(const Ray& ray) const {
    return intersect_pss(surface, ray, 0.0f, kInfinity, surface.params.max_iterations);
  }
  PSS_HOST_DEVICE Hit secondary(const Ray& ray, float t_max) const {
    return intersect_secondary(surface, ray, t_max, surface.params.max_iterations);
  }
  PSS_HOST_DEVICE float secondary_offset(const Hit& hit) const { return surface.params.secondary_offset * hit.scale; }
  PSS_HOST_DEVICE vec3 albedo(const Hit& hit, vec3 base) const {
    if (!surface.colors) return base;
    return interpolated_color(surface.grid, surface.colors, hit.point, base);
  }
};

// What colours the surface: the shading's albedo, or the samples' colours interpolated at
// each hit (points/sample_colors.hpp).
enum class SurfaceColor : unsigned char { albedo, samples };

// The host owner of everything a PointSurfaceView points to.
class PreparedCloud {
 public:
  // Runs the "Initial approximation" on `backend`, thins the polynomials (points/thinning.hpp)
  // and builds the BVH over those kept (on the host); the phases "preprocess" and
  // "acceleration structure" go to stats. SurfaceColor::samples keeps the cloud's colours
  // (an Error if it has none).
  PreparedCloud(const PointCloud& cloud, const RayPssParams& params, Backend backend, Stats& stats,
                SurfaceColor color = SurfaceColor::albedo);
  PreparedCloud(const PreparedCloud&) = delete;
  PreparedCloud& operator=(const PreparedCloud&) = delete;
  ~PreparedCloud();

  // Takes the parameters of `params` that the preparation does not depend on: ε, the
  // iterations and candidates per ray, the secondary rays' mode and offset, the borders, and the surface
  // operator among those prepared for (MLS always; APSS and RIMLS when the cloud was
  // prepared with one of them, which gives the grid the samples' normals; an Error
  // otherwise). A viewer changes them without preparing again. validate(params) first.
  void set_search(const RayPssParams& params);

  PointSurfaceView view() const;  // on the host
  // The view the kernels of `backend` read; the GPU's copy is uploaded once, on first use.
  PointSurfaceView view_on(Backend backend) const;
  std::span<const LocalPolynomial> locals() const { return locals_; }  // those kept, in BVH order
  std::int64_t left_out() const { return left_out_; }  // samples with < 3 neighbours
  // The samples' widths h_i: least, median, largest (the per-sample ones live in the grid).
  const SupportWidths& widths() const { return widths_; }
  int support_levels() const { return grid_.levels(); }
  NormalsUsed normals_used() const { return normals_used_; }  // the samples' normals, for APSS and RIMLS
  // The file's normals turned as contradicting the points (points/turn_flipped_normals.hpp).
  std::size_t normals_turned() const { return normals_turned_; }
  // The file's off their neighbours' planes, where all were left out (sample_normals.hpp: FileNormals).
  std::size_t file_normals_off() const { return file_normals_off_; }
  // The samples set aside as off the surface (points/outliers.hpp), none with OutlierPolicy::keep.
  const OutlierReport& outliers() const { return outliers_; }
  const Bvh& bvh() const { return bvh_; }
  const glm::dvec3& origin() const { return origin_; }  // the cloud's (cloud.hpp)

 private:
  glm::dvec3 origin_;
  RayPssParams params_;
  SupportWidths widths_;
  OutlierReport outliers_;
  SupportGrid grid_;
  std::vector<LocalPolynomial> locals_;
  std::vector<vec3> colors_;  // empty, or linear RGB in the grid's order
  std::int64_t left_out_ = 0;
  NormalsUsed normals_used_ = NormalsUsed::none;
  std::size_t normals_turned_ = 0, file_normals_off_ = 0;
  Bvh bvh_;
  struct DeviceCopy;
  mutable std::unique_ptr<DeviceCopy> device_;
};

// Throws Error for parameters that are not positive and finite.
void validate(const RayPssParams& params);

// Throws Error where the prepared cloud has no surface anywhere (no sample has 3 others in
// reach, every point set aside): an image with no hit is no result, as `pss project`'s
// check_some_projected says for points none of which was projected.
void check_some_surface(const PreparedCloud& cloud, const RayPssParams& params);

RenderedFrame render_cloud(const PreparedCloud& cloud, const Camera& camera, const TraceSettings& settings, Backend backend,
                           Stats& stats, FrameHits keep = FrameHits::all);

}  // namespace pss
