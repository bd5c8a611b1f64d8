#include "pss/points/render_cloud.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "pss/backend/cpu/parallel_for.hpp"
#include "pss/core/error.hpp"
#include "pss/points/project_cloud.hpp"
#include "unit_frame.hpp"

namespace pss {

void validate(const RayPssParams& p) {
  validate(p.projection);
  auto positive = [](float v) { return v > 0 && std::isfinite(v); };
  if (!positive(p.ball_radius)) throw Error("ball radius b must be a positive number (got " + std::to_string(p.ball_radius) + ")");
  if (!positive(p.epsilon)) throw Error("epsilon must be a positive number (got " + std::to_string(p.epsilon) + ")");
  if (!(p.secondary_offset >= 0) || !std::isfinite(p.secondary_offset))
    throw Error("secondary ray offset must be a non-negative number");
  if (p.max_iterations < 1) throw Error("iterations must be at least 1");
  if (p.max_candidates < 1) throw Error("candidates per ray must be at least 1");
}

namespace {

std::vector<LocalFit> fit_all(const UniformGrid& grid, const PointCloud& cloud, const RayPssParams& params,
                              Backend backend) {
  // In the grid's (cell-sorted) order, so that neighbouring samples share cached cells.
  const std::span<const vec3> points = grid.sorted_points();
  std::vector<vec3> hints(points.size(), vec3(0.0f));
  if (cloud.has_normals())
    for (std::size_t i = 0; i < points.size(); ++i) hints[i] = cloud.normals[grid.original_index()[i]];
  std::vector<LocalFit> fits(points.size());
  const float h = params.projection.h, rho = params.projection.rho;
  Progress progress("local polynomials", std::int64_t(points.size()));
  if (backend == Backend::cuda) {
    cuda::fit_local_polynomials(grid.view(), points, hints, h, rho, fits, &progress);
  } else {
    const GridView view = grid.view();
    cpu::parallel_for(std::int64_t(points.size()), [&](std::int64_t i) {
      fits[i] = fit_local_polynomial(view, points[i], hints[i], h, rho);
    }, &progress);
  }
  return fits;
}

// The range-query grid is part of the preprocessing (the paper's 3D neighbourhood texture).
UniformGrid timed_grid(const PointCloud& cloud, const ProjectionParams& projection, Stats& stats) {
  check_neighbourhood(projection, points_detail::unit_frame(cloud.positions).diagonal);
  const float rho = projection.rho;
  ScopedPhase phase(stats, "preprocess");
  return UniformGrid(cloud.positions, 0.5f * rho);
}

// What a ray can meet of sample i lies in B(p_i, b) and in the slab |z| ≤ height about its
// tangent plane (nearest_local_hit clips to both): a disc of radius b and that thickness,
// whose box is much flatter than the ball's where the normal is near an axis. Tighter
// nodes prune more of the ~16-fold overlap of the balls at b = h.
std::vector<Aabb> disc_boxes(const std::vector<LocalPolynomial>& locals, float b) {
  std::vector<Aabb> boxes(locals.size());
  for (std::size_t i = 0; i < locals.size(); ++i) {
    const vec3 n = locals[i].normal;
    const float height = std::min(locals[i].height, b);
    vec3 half;
    for (int k = 0; k < 3; ++k) half[k] = std::min(b, b * std::sqrt(std::max(0.0f, 1 - n[k] * n[k])) + height * std::abs(n[k]));
    boxes[i].lo = locals[i].origin - half;
    boxes[i].hi = locals[i].origin + half;
  }
  return boxes;
}

}  // namespace

PreparedCloud::PreparedCloud(const PointCloud& cloud, const RayPssParams& params, Backend backend, Stats& stats)
    : params_((validate(params), params)),
      grid_(timed_grid(cloud, params.projection, stats)),
      bvh_(std::span<const Aabb>{}) {
  {
    ScopedPhase phase(stats, "preprocess");
    for (const LocalFit& f : fit_all(grid_, cloud, params, backend)) {
      if (f.status == LocalFitStatus::too_few_neighbours)
        ++left_out_;
      else
        locals_.push_back(f.local);
    }
  }
  ScopedPhase phase(stats, "acceleration structure");
  for (LocalPolynomial& l : locals_) l.height = height_bound(l.g, params.ball_radius);
  bvh_ = Bvh(disc_boxes(locals_, params.ball_radius));
  std::vector<LocalPolynomial> ordered(locals_.size());
  for (std::size_t k = 0; k < ordered.size(); ++k) ordered[k] = locals_[bvh_.primitives()[k]];
  locals_ = std::move(ordered);
}

PointSurfaceView PreparedCloud::view() const {
  PointSurfaceView v;
  v.grid = grid_.view();
  v.bvh = bvh_.view();
  v.locals = locals_.data();
  v.params = params_;
  return v;
}

RenderedFrame render_cloud(const PreparedCloud& cloud, const Camera& camera, const TraceSettings& settings, Backend backend,
                   Stats& stats) {
  if (backend == Backend::cuda) return cuda::render_points(cloud.view(), camera, settings, stats);
  return render_frame_cpu(PointFinder{cloud.view()}, camera, settings, stats);
}

}  // namespace pss
