#include "pss/points/sample_normals.hpp"

#include <algorithm>
#include <atomic>

#include "pss/backend/mirror.hpp"
#include "pss/backend/parallel_for.hpp"
#include "pss/points/orient_normals.hpp"
#include "pss/points/outliers.hpp"
#include "pss/points/project_points.hpp"
#include "pss/points/turn_flipped_normals.hpp"
#include "pss/spatial/grid_mirror.hpp"

namespace pss {

namespace {

// A file's normal more than 45° off its neighbours' plane does not follow the points; where
// over a third do, the file's are no normals of this surface (random, or one direction for
// all): random ones lie that far off for 71 % of the samples, a CAD part's exact ones only on
// its creases, where the plane straddles two faces.
constexpr float kFollowsCos = 0.70710678f;
constexpr std::size_t kOffShareDenominator = 3;

// How many of the grid's samples (of those with 3 neighbours or more) have their normal
// more than 45° off the plane of their neighbours.
std::size_t normals_off_the_points(const SupportGrid& grid, std::span<const vec3> normals) {
  const SupportGridView view = grid.view();
  std::atomic<std::size_t> off{0};
  cpu::parallel_for(std::int64_t(normals.size()), [&](std::int64_t k) {
    if (off_its_neighbours(view, int(k), normals[std::size_t(k)])) off.fetch_add(1, std::memory_order_relaxed);
  });
  return off.load();
}

}  // namespace

vec3 file_normal_of(const SupportGrid& grid, std::span<const vec3> input_normals, std::size_t k,
                    std::span<const std::uint64_t> cloud_index) {
  vec3 n = input_normals[std::size_t(grid.original_index()[k])];
  const std::span<const int> members = grid.members(k);
  if (!members.empty()) {  // merged: the mean of its points' normals, each turned to the sample's own side
    const vec3 own = n;
    n = vec3(0.0f);
    // Summed in the cloud's order, whatever the input's (a tile's set: its own points first).
    thread_local std::vector<std::pair<std::uint64_t, int>> in_order;
    in_order.clear();
    for (const int j : members)
      in_order.push_back({cloud_index.empty() ? std::uint64_t(j) : cloud_index[std::size_t(j)], j});
    std::sort(in_order.begin(), in_order.end());
    for (const auto& [index, j] : in_order) {
      const vec3 m = input_normals[std::size_t(j)];
      n += glm::dot(m, own) < 0 ? -m : m;
    }
  }
  return has_direction(n) ? n / glm::length(n) : vec3(0.0f);
}

bool off_its_neighbours(const SupportGridView& view, int k, vec3 normal) {
  const NeighboursPlane plane = neighbours_plane(view, k);
  return plane.fitted && std::abs(glm::dot(plane.normal, normal)) < kFollowsCos;
}

bool too_many_off(std::size_t off, std::size_t samples) { return off * kOffShareDenominator > samples; }

vec3 hint_beside(const SupportGridView& view, std::span<const vec3> sorted_normals, vec3 position, vec3 normal) {
  const float length = glm::length(normal);
  if (!(length > 0) || !std::isfinite(length)) return vec3(0.0f);
  normal /= length;
  const int nearest = view.nearest_covering(position);
  const vec3 beside = nearest < 0 ? vec3(0.0f) : sorted_normals[std::size_t(nearest)];
  return glm::dot(normal, beside) < 0 ? -normal : normal;
}

FileNormals file_normals(const SupportGrid& grid, std::span<const vec3> input_normals, const ProjectionParams& params,
                         Stats& stats) {
  FileNormals file;
  if (input_normals.empty() || params.normals != NormalSource::file) return file;
  file.sorted.resize(grid.original_index().size());
  for (std::size_t k = 0; k < file.sorted.size(); ++k) {
    file.sorted[k] = file_normal_of(grid, input_normals, k, {});
    if (!has_direction(file.sorted[k])) return {};
  }
  ScopedPhase phase(stats, "check file normals");
  file.off_the_points = normals_off_the_points(grid, file.sorted);
  if (too_many_off(file.off_the_points, file.sorted.size())) return {{}, 0, file.off_the_points};
  file.off_the_points = 0;
  file.turned = turn_flipped_normals(grid, file.sorted);
  if (face_file_normals_as_seen(grid, file.sorted) > 0) {  // counted anew: those that face against the file's
    file.turned = 0;
    for (std::size_t k = 0; k < file.sorted.size(); ++k)
      file.turned += glm::dot(file.sorted[k], file_normal_of(grid, input_normals, k, {})) < 0;
  }
  return file;
}

ProjectionParams sample_plane_params(const ProjectionParams& params) {
  ProjectionParams plane = params;
  plane.surface = SurfaceOperator::mls;
  plane.plane = PlaneFitMethod::wls;
  plane.borders = BorderMode::extend;  // a sample's plane, wherever it lies
  return plane;
}

std::vector<vec3> sample_normals(const SupportGrid& grid, const FileNormals& file, const ProjectionParams& params,
                                 Backend backend, Stats& stats, NormalsUsed& used) {
  if (!file.sorted.empty()) {
    used = NormalsUsed::file;
    return file.sorted;
  }
  used = NormalsUsed::estimated;
  std::vector<vec3> normals;
  std::vector<ProjectionStatus> status;  // whether each plane was fitted: which may seed the orientation
  const std::size_t n = grid.sorted_points().size();
  const ProjectionParams plane = sample_plane_params(params);
  {
    const GridMirror g(backend, grid);
    normals.resize(n);
    status.resize(n);
    Progress progress("sample normals", std::int64_t(n));
    // In chunks, as the projections (projection_chunk): the fits are never all held beside the
    // normals (issue 28: at 10^6 points they set the run's peak).
    const std::size_t chunk = projection_chunk(backend);
    for (std::size_t begin = 0; begin < n; begin += chunk) {
      const std::size_t size = std::min(chunk, n - begin);
      Mirror<ProjectedPoint> out(backend, size);
      parallel_for(backend, "sample normals", std::int64_t(size),
                   ProjectPointsKernel{g.view(), g.view().points + begin, nullptr, out.data(), plane}, stats,
                   &progress);
      const std::vector<ProjectedPoint> fitted = out.take();
      for (std::size_t k = 0; k < size; ++k) {
        normals[begin + k] = fitted_normal(fitted[k]);
        status[begin + k] = fitted[k].status;
      }
    }
  }
  ScopedPhase phase(stats, "orient normals", false);  // its Progress shows it
  orient_grid_normals(grid, normals, status);  // the samples of each N(p_i) linked
  // The tree's signs hold a seam where it crossed a fold whose plane fits straddle both walls
  // (one wrong normal there turned 12,700 of the dragon's samples inward): the seams' turn
  // mends it, as a file's.
  turn_flipped_normals(grid, normals);
  return normals;
}

void prepare_sample_normals(SupportGrid& grid, const FileNormals& file, const ProjectionParams& params, Backend backend,
                            Stats& stats, NormalsUsed& used) {
  used = NormalsUsed::none;
  if (params.surface == SurfaceOperator::mls) return;
  grid.set_normals(sample_normals(grid, file, params, backend, stats, used));
}

const char* normals_used_name(NormalsUsed used) {
  switch (used) {
    case NormalsUsed::file: return "file";
    case NormalsUsed::estimated: return "estimated";
    case NormalsUsed::none: break;
  }
  return "none";
}

}  // namespace pss
