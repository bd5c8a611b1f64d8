#include "pss/points/render_cloud.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include <glm/geometric.hpp>

#include "pss/backend/mirror.hpp"
#include "pss/backend/parallel_for.hpp"
#include "pss/core/error.hpp"
#include "pss/points/outliers.hpp"
#include "pss/points/project_cloud.hpp"
#include "pss/points/sample_normals.hpp"
#include "pss/points/thinning.hpp"
#include "pss/render/image.hpp"
#include "pss/render/render_frame.hpp"
#include "pss/spatial/grid_mirror.hpp"

namespace pss {

void validate(const RayPssParams& p) {
  validate(p.projection);
  auto positive = [](float v) { return v > 0 && std::isfinite(v); };
  if (!positive(p.ball_radius)) throw Error("ball radius b must be a positive number (got " + std::to_string(p.ball_radius) + ")");
  // A polynomial fitted over the support ρ says nothing beyond it: with b of several ρ the
  // rays met the polynomials' far reaches, and every hit was a capped, unconverged candidate
  // up to 5 units off a unit sphere (--b 10).
  if (p.ball_radius > p.projection.rho) {
    char message[300];
    std::snprintf(message, sizeof message,
                  "the ball radius b = %g is larger than rho = %g: a sample's polynomial would reach past the samples "
                  "it was fitted to (b is h by default)",
                  double(p.ball_radius), double(p.projection.rho));
    throw Error(message);
  }
  if (!positive(p.epsilon)) throw Error("epsilon must be a positive number (got " + std::to_string(p.epsilon) + ")");
  if (!(p.ball_spacing >= 0) || !(p.ball_spacing <= p.ball_radius)) {
    char message[200];
    std::snprintf(message, sizeof message, "ball spacing must be a number from 0 to b = %g (got %g)",
                  double(p.ball_radius), double(p.ball_spacing));
    throw Error(message);
  }
  if (!(p.secondary_offset >= 0) || !std::isfinite(p.secondary_offset))
    throw Error("secondary ray offset must be a non-negative number");
  if (p.max_iterations < 1) throw Error("iterations must be at least 1");
  if (p.max_candidates < 1 || p.max_candidates > kMaxCandidates)
    throw Error("candidates per ray must be from 1 to " + std::to_string(kMaxCandidates));
}

namespace {

std::vector<LocalFit> fit_all(const SupportGrid& grid, const FileNormals& file, const RayPssParams& params,
                              Backend backend, Stats& stats) {
  // In the grid's (cell-sorted) order, so that neighbouring samples share cached cells.
  const std::size_t n = grid.sorted_points().size();
  std::vector<vec3> hints = file.sorted;
  hints.resize(n, vec3(0.0f));
  const GridMirror g(backend, grid);
  const Mirror<vec3> hint(backend, hints);
  Mirror<LocalFit> fits(backend, n);
  Progress progress("local polynomials", std::int64_t(n));
  parallel_for(backend, "local polynomials", std::int64_t(n),
               FitLocalPolynomialsKernel{g.view(), hint.data(), fits.data(), params.ball_radius / params.projection.h},
               stats, &progress);
  return fits.take();
}

// The samples' widths and the range-query grid are part of the preprocessing (the paper's 3D
// neighbourhood texture).
SupportGrid timed_grid(const PointCloud& cloud, const ProjectionParams& projection, Backend backend, Stats& stats,
                       SupportWidths& widths, OutlierReport& outliers) {
  const Aabb box = cloud.bounds();  // its diagonal in double, as the unit frame's
  check_neighbourhood(projection, glm::length(glm::dvec3(box.hi) - glm::dvec3(box.lo)), cloud.size());
  {
    ScopedPhase phase(stats, "support widths", projection.support == Support::global);  // else its Progress shows it
    widths = support_widths(cloud.positions, projection);
  }
  // Counting sorts (not timed: the fits after them are what takes time), and the outliers'
  // test, timed by its kernel.
  SupportGrid grid = grid_of_samples(cloud.positions, widths.h, widths.merged, projection.rho / projection.h, projection.outliers,
                                     backend, stats, outliers);
  widths.h = {};  // the grid keeps them
  widths.merged = {};
  return grid;
}

// What a ray can meet of sample i lies in B(p_i, b_i) and in the slab |z| ≤ height about its
// tangent plane (nearest_local_hit clips to both): a disc of radius b_i and that thickness,
// whose box is much flatter than the ball's where the normal is near an axis. Tighter
// nodes prune more of the ~16-fold overlap of the balls at b = h.
std::vector<Aabb> disc_boxes(const std::vector<LocalPolynomial>& locals) {
  std::vector<Aabb> boxes(locals.size());
  for (std::size_t i = 0; i < locals.size(); ++i) {
    const float b = locals[i].radius;
    const vec3 n = locals[i].normal;
    const float height = std::min(locals[i].height, b);
    vec3 half;
    for (int k = 0; k < 3; ++k) half[k] = std::min(b, b * std::sqrt(std::max(0.0f, 1 - n[k] * n[k])) + height * std::abs(n[k]));
    boxes[i].lo = locals[i].origin - half;
    boxes[i].hi = locals[i].origin + half;
  }
  return boxes;
}

// The cloud's colours in linear light, in the grid's order of the samples, so that a kernel
// reads sample i's colour where the grid walk reads its position.
std::vector<vec3> linear_colors(const SupportGrid& grid, const PointCloud& cloud) {
  if (!cloud.has_colors()) throw Error("the point cloud has no per-point colours");
  const std::span<const int> original = grid.original_index();
  auto linear = [&](int i) {
    const Rgb8 c = cloud.colors[std::size_t(i)];
    return vec3(srgb8_to_linear(c.r), srgb8_to_linear(c.g), srgb8_to_linear(c.b));
  };
  std::vector<vec3> colors(original.size());
  for (std::size_t i = 0; i < colors.size(); ++i) {
    const std::span<const int> members = grid.members(i);  // a merged sample's colour: its points' mean
    if (members.empty()) {
      colors[i] = linear(original[i]);
      continue;
    }
    vec3 sum(0.0f);
    for (const int j : members) sum += linear(j);
    colors[i] = sum / float(members.size());
  }
  return colors;
}

}  // namespace

// The arrays of a PointSurfaceView in device memory, uploaded on the first GPU frame.
struct PreparedCloud::DeviceCopy {
  explicit DeviceCopy(const PreparedCloud& cloud)
      : grid(Backend::cuda, cloud.grid_),
        nodes(Backend::cuda, std::span<const BvhNode>(cloud.bvh_.view().nodes, std::size_t(cloud.bvh_.view().node_count))),
        primitives(Backend::cuda, cloud.bvh_.primitives()),
        locals(Backend::cuda, cloud.locals_),
        colors(Backend::cuda, cloud.colors_),
        view(cloud.view()) {
    view.grid = grid.view();
    view.bvh.nodes = nodes.data();
    view.bvh.primitives = primitives.data();
    view.locals = locals.data();
    view.colors = cloud.colors_.empty() ? nullptr : colors.data();
  }
  GridMirror grid;
  Mirror<BvhNode> nodes;
  Mirror<int> primitives;
  Mirror<LocalPolynomial> locals;
  Mirror<vec3> colors;
  PointSurfaceView view;
};

void check_some_surface(const PreparedCloud& cloud, const RayPssParams& params) {
  if (!cloud.locals().empty()) return;
  char message[300];
  std::snprintf(message, sizeof message,
                "no surface with h = %g, rho = %g (%lld points set aside, %lld samples with fewer than 3 neighbours); "
                "h is likely too small for the sample spacing (pss info suggests one)",
                double(params.projection.h), double(params.projection.rho), (long long)cloud.outliers().set_aside,
                (long long)cloud.left_out());
  throw Error(message);
}

PreparedCloud::PreparedCloud(const PointCloud& cloud, const RayPssParams& params, Backend backend, Stats& stats,
                             SurfaceColor color)
    : origin_(cloud.origin),
      params_((validate(params), params)),
      grid_(timed_grid(cloud, params.projection, backend, stats, widths_, outliers_)),
      bvh_(std::span<const Aabb>{}) {
  const FileNormals file = file_normals(grid_, cloud.normals, params.projection, stats);
  normals_turned_ = file.turned;
  file_normals_off_ = file.off_the_points;
  prepare_sample_normals(grid_, file, params.projection, backend, stats, normals_used_);
  {
    ScopedPhase phase(stats, "preprocess");
    if (color == SurfaceColor::samples) colors_ = linear_colors(grid_, cloud);
    for (const LocalFit& f : fit_all(grid_, file, params, backend, stats)) {
      if (f.status == LocalFitStatus::too_few_neighbours)
        ++left_out_;
      else
        locals_.push_back(f.local);
    }
  }
  ScopedPhase phase(stats, "acceleration structure");
  const float b = params.ball_radius;
  locals_ = thin_local_polynomials(locals_, params.ball_spacing / b, kThinningTolerance * params.projection.h / b);
  for (LocalPolynomial& l : locals_) l.height = height_bound(l.g, l.radius) + coordinate_rounding(l.origin);
  bvh_ = Bvh(disc_boxes(locals_));
  std::vector<LocalPolynomial> ordered(locals_.size());
  for (std::size_t k = 0; k < ordered.size(); ++k) ordered[k] = locals_[bvh_.primitives()[k]];
  locals_ = std::move(ordered);
}

void PreparedCloud::set_search(const RayPssParams& p) {
  validate(p);
  params_.epsilon = p.epsilon;
  params_.max_iterations = p.max_iterations;
  params_.max_candidates = p.max_candidates;
  params_.secondary = p.secondary;
  params_.secondary_offset = p.secondary_offset;
  params_.projection.borders = p.projection.borders;
  if (p.projection.surface != SurfaceOperator::mls && grid_.normals().empty())
    throw Error("the cloud was prepared without the samples' normals that APSS and RIMLS need; prepare it again");
  params_.projection.surface = p.projection.surface;
}

PointSurfaceView PreparedCloud::view() const {
  PointSurfaceView v;
  v.grid = grid_.view();
  v.bvh = bvh_.view();
  v.locals = locals_.data();
  v.colors = colors_.empty() ? nullptr : colors_.data();
  v.params = params_;
  return v;
}

PreparedCloud::~PreparedCloud() = default;

PointSurfaceView PreparedCloud::view_on(Backend backend) const {
  if (backend == Backend::cpu) return view();
  if (!device_) device_ = std::make_unique<DeviceCopy>(*this);
  PointSurfaceView v = device_->view;
  v.params = params_;  // set_search may have changed them since the upload
  return v;
}

RenderedFrame render_cloud(const PreparedCloud& cloud, const Camera& camera, const TraceSettings& settings, Backend backend,
                           Stats& stats, FrameHits keep) {
  RenderedFrame frame = render_frame(backend, PointFinder{cloud.view_on(backend)}, camera, settings, stats, keep);
  frame.origin = cloud.origin();
  return frame;
}

}  // namespace pss
