#include "pss/points/project_cloud.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "pss/backend/cpu/parallel_for.hpp"
#include "pss/backend/mirror.hpp"
#include "pss/backend/parallel_for.hpp"
#include "pss/core/error.hpp"
#include "pss/core/gather.hpp"
#include "pss/core/memory.hpp"
#include "pss/points/orient_normals.hpp"
#include "pss/points/outliers.hpp"
#include "pss/points/sample_normals.hpp"
#include "pss/points/support.hpp"
#include "pss/spatial/grid_mirror.hpp"
#include "pss/points/unit_frame.hpp"

namespace pss {

void validate(const ProjectionParams& p) {
  auto positive = [](float v) { return v > 0 && std::isfinite(v); };
  if (!positive(p.h)) throw Error("h must be a positive number (got " + std::to_string(p.h) + ")");
  if (!positive(p.rho)) throw Error("rho must be a positive number (got " + std::to_string(p.rho) + ")");
  if (p.max_mls_iterations < 1) throw Error("MLS iterations must be at least 1");
}

ProjectionParams in_unit_frame(const ProjectionParams& params, double scale) {
  ProjectionParams unit = params;
  unit.h = float(double(params.h) / scale);
  unit.rho = float(double(params.rho) / scale);
  unit.t_tolerance = float(double(params.t_tolerance) / scale);
  return unit;
}

void check_neighbourhood(const ProjectionParams& p, double diagonal, std::uint64_t points) {
  // With --h a cloud whose points all coincide got a disc rendered, and every point
  // projected "converged" with a normal of no data's.
  if (diagonal == 0 && points > 1) throw Error("the points all coincide: they define no surface");
  // A ball wider than the whole cloud holds every point: each projection would fit the
  // entire cloud (quadratic work, a useless global plane) and a uniform grid of cells that
  // wide has nothing to index.
  if (diagonal > 0 && double(p.rho) > diagonal) {
    char message[300];
    std::snprintf(message, sizeof message,
                  "the neighbourhood radius rho = %g (h = %g) is larger than the cloud's bounding-box diagonal %g: "
                  "every neighbourhood would hold the whole cloud; use a smaller --h or --rho",
                  double(p.rho), double(p.h), diagonal);
    throw Error(message);
  }
}

void check_some_projected(const StatusCounts& c, const ProjectionParams& params) {
  if (c.converged + c.not_converged + c.too_few_neighbours + c.degenerate_normal == 0 ||
      c.converged + c.not_converged > 0)
    return;
  // Neighbourhoods on a line (a cloud of one line, or of rows farther apart than h) fit no
  // plane; too few neighbours is an h below the spacing.
  const char* why = c.degenerate_normal > c.too_few_neighbours
                        ? "the points within reach of each lie on a line or coincide, which fits no plane (a larger "
                          "h may reach across to other lines)"
                        : "h is likely too small for the sample spacing (pss info suggests one)";
  char message[400];
  std::snprintf(message, sizeof message,
                "no point was projected with h = %g, rho = %g (too few neighbours %lld, degenerate normal %lld); %s",
                double(params.h), double(params.rho), (long long)c.too_few_neighbours,
                (long long)c.degenerate_normal, why);
  throw Error(message);
}

namespace {

// Where samples were merged (merged_samples.hpp), each merged sample's cube holds tens of
// points within h_i of one another, and each point's ρ_i, as wide as the noise, links it to
// thousands: the tree over every point took 30 of `pss project`'s 46 s on a 300,000-point
// noisy torus. So the tree grows over the points that stand for themselves, each sample's
// own (its cube's first) and those of no sample (set aside), with each part's vote; every
// other point takes the side of its sample's point, whose normal, a cube away on a surface
// smooth at h_i, is nearly its own. sample_of[i]: the point whose sample i joined, or −1.
void orient_through_samples(std::vector<vec3>& positions, std::vector<vec3>& normals, std::vector<float> support,
                            std::span<const ProjectionStatus> status, std::span<const int> sample_of) {
  std::vector<int> nodes;
  for (std::size_t i = 0; i < sample_of.size(); ++i)
    if (sample_of[i] < 0 || std::size_t(sample_of[i]) == i) nodes.push_back(int(i));
  std::vector<vec3> at = gathered<vec3>(positions, nodes);
  std::vector<vec3> facing = gathered<vec3>(normals, nodes);
  std::vector<float> rho = gathered<float>(support, nodes);
  const std::vector<ProjectionStatus> state = gathered(status, nodes);
  release(support);
  orient_normals_consistently(at, facing, std::move(rho), state);
  for (std::size_t k = 0; k < nodes.size(); ++k) normals[std::size_t(nodes[k])] = facing[k];
  for (std::size_t i = 0; i < sample_of.size(); ++i) {
    const int j = sample_of[i];
    if (j >= 0 && std::size_t(j) != i && glm::dot(normals[i], normals[std::size_t(j)]) < 0) normals[i] = -normals[i];
  }
}

}  // namespace

CloudProjection project_cloud(PointCloud input, const ProjectionParams& params, Backend backend, Stats& stats) {
  validate(params);
  const std::size_t n = input.size();
  // Projection runs in the cloud's unit frame (unit_frame.hpp): h, ρ and the tolerance are
  // lengths, so they scale with the points; the results are mapped back at the end.
  const UnitFrame frame = unit_frame(input.positions);
  check_neighbourhood(params, frame.diagonal, n);
  const ProjectionParams unit_params = in_unit_frame(params, frame.scale);
  CloudProjection out;
  // The projections keep the input's order, so its per-point values stay with them; the
  // input's arrays become the output's (issue 28: one copy of each at 10^7 points).
  out.cloud.origin = input.origin;
  out.cloud.colors = std::move(input.colors);
  out.cloud.scalars = std::move(input.scalars);
  std::vector<vec3>& positions = out.cloud.positions;
  positions = std::move(input.positions);
  // The widths of the points as read, then taken to the unit frame, as tile by tile
  // (tiles/support.hpp), so that both get them to the last bit.
  SupportWidths widths;
  {
    ScopedPhase phase(stats, "support widths", params.support == Support::global);  // else its Progress shows it
    widths = support_widths(positions, params);
  }
  for (float& w : widths.h) w = float(double(w) / frame.scale);
  for (vec3& p : positions) p = frame.to_unit(p);
  NormalsUsed normals_used = NormalsUsed::none;
  OutlierReport outliers;
  std::size_t normals_turned = 0, file_normals_off = 0;
  bool file_hints = false;  // the file's normals orient the projections
  bool orient_after = false;  // MLS's projections without them: orient_normals_consistently
  std::vector<int> sample_of;  // where samples were merged: orient_through_samples
  {  // what the projection needs, freed before the orientation
    ScopedPhase phase(stats, "spatial index");
    SupportGrid grid =
        grid_of_samples(positions, widths.h, widths.merged, unit_params.rho / unit_params.h, params.outliers, backend, stats, outliers);
    phase.stop();
    release(widths.merged);  // the grid holds the merged samples
    const FileNormals file = file_normals(grid, input.normals, unit_params, stats);
    normals_turned = file.turned;
    file_normals_off = file.off_the_points;
    file_hints = !file.sorted.empty();
    orient_after = !file_hints && params.surface == SurfaceOperator::mls;
    if (!orient_after) release(widths.h);  // the orientation's supports, else the grid's alone
    prepare_sample_normals(grid, file, unit_params, backend, stats, normals_used);
    if (!grid.masses().empty() && orient_after) {  // for the orientation: whose sample each point joined
      sample_of.assign(n, -1);
      for (std::size_t k = 0; k < grid.original_index().size(); ++k)
        for (const int j : grid.members(k)) sample_of[std::size_t(j)] = grid.original_index()[k];
    }
    // The points set aside are not samples, but points all the same: projected after the
    // samples, with a hint from the nearest sample where the file has normals. Where samples
    // were merged, a merged sample's position is its cube's mean, not its point's: every
    // point is projected as these are, gathered from `positions` itself a chunk at a time (at
    // 10⁷ points a copy and its indices were 160 MB of the run's peak).
    const std::span<const int> original = grid.original_index();
    const bool every_point = !grid.masses().empty();
    const std::size_t m = every_point ? 0 : original.size();
    std::vector<int> set_aside;
    if (!every_point && m < n) {
      std::vector<char> sample(n, 0);
      for (std::size_t k = 0; k < m; ++k) sample[std::size_t(original[k])] = 1;
      for (std::size_t i = 0; i < n; ++i)
        if (!sample[i]) set_aside.push_back(int(i));
    }
    const std::size_t other_count = every_point ? n : set_aside.size();
    const auto other_index = [&](std::size_t k) { return every_point ? k : std::size_t(set_aside[k]); };
    std::vector<vec3> others, other_hints;
    for (std::size_t k = 0; k < other_count; ++k) {
      const std::size_t i = other_index(k);
      if (!every_point) others.push_back(positions[i]);
      // A point set aside is no sample, so the turn of the file's normals did not see it.
      if (file_hints) other_hints.push_back(hint_beside(grid.view(), file.sorted, positions[i], input.normals[i]));
    }
    release(input.normals);  // their hints are taken
    out.cloud.normals.resize(n);
    out.status.resize(n);
    const GridMirror g(backend, grid);
    const Mirror<vec3> hint(backend, file.sorted);
    Progress progress("projecting", std::int64_t(n));
    // In chunks (projection_chunk), each placed at once, so that the projections are never all
    // held beside the output. A chunk's kernel reads its own points only, so `positions` may
    // take each chunk's projections.
    const std::size_t chunk = projection_chunk(backend);
    // points[k], hints[k] (or null) are those of input point index(k), k < count; with
    // `gather`, points[index(k)] and hints[index(k)] are.
    std::vector<vec3> gathered_points, gathered_hints;
    auto project = [&](const vec3* points, const vec3* hints, std::size_t count, auto index, bool gather) {
      for (std::size_t begin = 0; begin < count; begin += chunk) {
        const std::size_t size = std::min(chunk, count - begin);
        if (gather) {
          gathered_points.resize(size);
          gathered_hints.resize(hints ? size : 0);
          for (std::size_t k = 0; k < size; ++k) gathered_points[k] = points[index(begin + k)];
          for (std::size_t k = 0; k < gathered_hints.size(); ++k) gathered_hints[k] = hints[index(begin + k)];
        }
        const Mirror<vec3> chunk_points(backend, gathered_points);
        const Mirror<vec3> chunk_hints(backend, gathered_hints);
        Mirror<ProjectedPoint> projected(backend, size);
        parallel_for(backend, "projection", std::int64_t(size),
                     ProjectPointsKernel{g.view(), gather ? chunk_points.data() : points + begin,
                                         !hints ? nullptr : gather ? chunk_hints.data() : hints + begin,
                                         projected.data(), unit_params},
                     stats, &progress);
        const std::vector<ProjectedPoint> done = projected.take();
        cpu::parallel_for(std::int64_t(size), [&](std::int64_t k) {
          const std::size_t i = index(begin + std::size_t(k));
          positions[i] = done[std::size_t(k)].point;
          out.cloud.normals[i] = done[std::size_t(k)].normal;
          out.status[i] = done[std::size_t(k)].status;
        });
      }
    };
    // The samples are read from the grid, so the positions take the projections as they come.
    // The samples in the grid's order, so that neighbouring threads gather neighbouring
    // samples from the cache; in a scan's random order, 10⁷ points projected at a fifth of
    // the rate of 10⁶ on a GPU (docs/benchmarks.md, issue 29). Without input normals the
    // eigenvector's sign is arbitrary; orientation comes after.
    project(g.view().points, file_hints ? hint.data() : nullptr, m,
            [&](std::size_t k) { return std::size_t(original[k]); }, false);
    if (every_point) {
      // Every point, where samples were merged: in the order of the grid's cells too, not the
      // file's (a scan's, or a generated cloud's random order), so that neighbouring threads
      // and chunks gather the same samples from the cache.
      const std::vector<int> by_cell = grid.cell_order(positions);
      project(positions.data(), file_hints ? other_hints.data() : nullptr, n,
              [&](std::size_t k) { return std::size_t(by_cell[k]); }, true);
    } else {
      const Mirror<vec3> other(backend, others);
      const Mirror<vec3> other_hint(backend, other_hints);
      project(other.data(), file_hints ? other_hint.data() : nullptr, other_count, other_index, false);
    }
  }
  out.widths.least = widths.least;  // as read
  out.widths.median = widths.median;
  out.widths.largest = widths.largest;
  out.widths.merged_count = widths.merged_count;
  for (const ProjectionStatus status : out.status) out.counts.add(status);
  out.normals = normals_used;
  out.normals_turned = normals_turned;
  out.file_normals_off = file_normals_off;
  out.outliers = outliers;
  // APSS's and RIMLS's normals follow the samples' oriented ones already.
  if (orient_after) {
    ScopedPhase phase(stats, "orient normals", false);  // its Progress shows it
    std::vector<float> support = std::move(widths.h);  // ρ_i: the orientation links the samples of each N(p_i)
    for (float& rho : support) rho *= unit_params.rho / unit_params.h;
    if (sample_of.empty())
      orient_normals_consistently(positions, out.cloud.normals, std::move(support), out.status);
    else
      orient_through_samples(positions, out.cloud.normals, std::move(support), out.status, sample_of);
  }
  for (vec3& p : positions) p = frame.from_unit(p);
  return out;
}

}  // namespace pss
