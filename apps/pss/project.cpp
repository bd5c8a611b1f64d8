// pss project FILE -o OUT.ply|.xyz: every point moved onto the PSS, with its normal and, in a
// PLY, the input's colours and scalars and how its projection ended.
#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "commands.hpp"
#include "in_tiles_or_core.hpp"
#include "numbers.hpp"
#include "output_options.hpp"
#include "pss/core/error.hpp"
#include "pss/core/text.hpp"
#include "pss/io/output_file.hpp"
#include "pss/io/point_cloud_file.hpp"
#include "pss/io/point_cloud_writer.hpp"
#include "pss/io/point_stream.hpp"
#include "pss/io/tiled_cloud.hpp"
#include "pss/points/project_cloud.hpp"
#include "pss/points/surface_stats.hpp"
#include "pss/tiles/memory_plan.hpp"
#include "pss/tiles/project.hpp"
#include "pss/tiles/spacing.hpp"
#include "pss/tiles/support.hpp"
#include "ranks/ranks.hpp"

namespace pss::app {

namespace {

struct ProjectOptions {
  std::string input, output;
  std::string method = "mls";
  CloudSurfaceFlags surface;
  ComputeOptions compute;
  std::string memory;  // --memory SIZE
};

// Bytes a point (tiles/memory_plan.hpp): in core, above what the noisy tori take (2026-11-30,
// docs/benchmarks.md: 10^6 points MLS 76, RIMLS 90; 10^7 63) for a cloud whose grid takes
// more cells a sample (up to 32 of 4 bytes, spatial/support_grid.hpp); beside the tiles, each
// point's width, whether it is a sample and whether it merges, and in the outliers' passes
// its distance, neighbours' mass and mass (a copy of one for a median without masses); a
// tile's point, its record, unit position, width, merged sample, grid and projection, and in
// the orientation its record, tree and parts.
// APSS and RIMLS: a tile's point also carries its sample's normal in the set, the request and
// the grid (the projection's peak 15 % higher on a 300,000-point torus at --memory 24M).
constexpr MemoryCosts kProjectCosts{160, 24, 256};
constexpr MemoryCosts kProjectCostsWithNormals{160, 24, 320};

// What pss project says of a run, in core or tile by tile.
struct ProjectRun {
  std::uint64_t points = 0;
  glm::dvec3 origin{0.0};
  StatusCounts counts;
  SupportWidths widths;
  NormalsUsed normals = NormalsUsed::none;
  std::size_t normals_turned = 0;
  std::size_t file_normals_off = 0;  // where all were left out as not following the points
  std::size_t normals_without_direction = 0;  // the file's: then all were left out
  std::int64_t set_aside = 0;
  std::string memory;  // how the run held the cloud, for the summary
  std::vector<std::uint64_t> points_per_rank;  // the points each rank projected
};

PlaneFitMethod plane_of(const ProjectOptions& o) { return o.method == "wls" ? PlaneFitMethod::wls : PlaneFitMethod::mls; }

void check_projected(const ProjectOptions& o, const StatusCounts& counts, const ProjectionParams& params) {
  naming_input(o.input, [&] { check_some_projected(counts, params); });
}

ProjectRun project_in_core(const ProjectOptions& o, Backend backend, Stats& stats, ProjectionParams& params) {
  PointCloud cloud = read_cloud(o.input, stats);
  params = projection_params(o.surface, cloud, o.input, plane_of(o), stats);
  const std::size_t without_direction = file_normals_without_direction(cloud, o.surface.surface);
  // The input's arrays become the output's (issue 28). What the cloud cannot give (a
  // neighbourhood wider than it) names it.
  const CloudProjection result =
      naming_input(o.input, [&] { return project_cloud(std::move(cloud), params, backend, stats); });
  check_projected(o, result.counts, params);
  {
    ScopedPhase phase(stats, "write");
    std::vector<std::int32_t> status(result.status.size());
    for (std::size_t i = 0; i < status.size(); ++i) status[i] = std::int32_t(result.status[i]);
    const PlyIntProperty extra[] = {{"status", status}};
    write_point_cloud(o.output, result.cloud, extra);
  }
  std::vector<std::uint64_t> per_rank(std::size_t(rank_count()), 0);
  per_rank[0] = result.cloud.size();
  return {result.cloud.size(), result.cloud.origin, result.counts, result.widths, result.normals,
          result.normals_turned, result.file_normals_off, without_direction, result.outliers.set_aside, "in core", per_rank};
}

// The file's next `count` points (their colours and scalars) into `part`.
void read_points(PointStream& stream, PointPart& part, std::size_t count, const std::string& file) {
  part.clear();
  while (part.size() < count)
    if (stream.read(part, count - part.size()) == 0)
      throw file_error(file, "changed while it was read: it has fewer points than before");
}

// A cloud larger than the budget, tile by tile (issue 28): the in-core points, in its order,
// written a window at a time beside the file's colours and scalars, read again.
ProjectRun project_in_tiles(const ProjectOptions& o, const MemoryPlan& plan, Backend backend, Stats& stats,
                            ProjectionParams& params) {
  std::optional<TiledCloud> read;
  {
    ScopedPhase phase(stats, "read", false);  // its Progress shows it
    read.emplace(o.input, scratch_folder(), plan.points_per_tile, plan.buffer_bytes);
  }
  const TiledCloud& tiles = *read;
  params = projection_params(
      o.surface,
      [&] { return naming_input(o.input, [&] { return float(estimate_spacing(tiles).suggested_h); }); },
      plane_of(o), stats);
  // A window's points take about 128 bytes: its results, the file's part and the writer's.
  const std::size_t window = std::size_t(std::clamp<std::uint64_t>(plan.budget / 8 / 128, 4096, 1u << 24));
  const TiledProjection projected(tiles, params, backend, scratch_folder(), window, plan.buffer_bytes, stats,
                                  rank_farm());
  check_projected(o, projected.counts(), params);
  {
    ScopedPhase phase(stats, "write", false);
    Progress progress("writing", std::int64_t(tiles.size()));
    const auto stream = open_point_stream(o.input);
    PointPart part;
    read_points(*stream, part, std::min<std::uint64_t>(window, tiles.size()), o.input);
    PointsLayout layout;
    layout.count = tiles.size();
    layout.origin = tiles.origin();
    layout.normals = true;
    layout.colors = tiles.has_colors();
    for (const ScalarProperty& scalar : part.scalars) layout.scalars.push_back({scalar.name, scalar.type, {}});
    layout.extra = {"status"};
    PointCloudWriter writer(o.output, layout);
    projected.read_in_order([&](ProjectedWindow& w) {
      if (w.first > 0) read_points(*stream, part, w.positions.size(), o.input);
      std::vector<std::int32_t> status(w.status.size());
      for (std::size_t i = 0; i < status.size(); ++i) status[i] = std::int32_t(w.status[i]);
      const std::size_t count = w.positions.size();
      PointCloud out;
      out.origin = tiles.origin();
      out.positions = std::move(w.positions);
      out.normals = std::move(w.normals);
      out.colors = std::move(part.colors);
      out.scalars = std::move(part.scalars);
      const PlyIntProperty extra[] = {{"status", status}};
      writer.append(out, extra);
      part.colors = std::move(out.colors);
      part.scalars = std::move(out.scalars);  // their names and types for the next window
      progress.advance(std::int64_t(count));
    });
    part.clear();
    if (stream->read(part, 1) > 0) throw file_error(o.input, "changed while it was read: it has more points than before");
    writer.commit();
  }
  return {tiles.size(), tiles.origin(), projected.counts(), projected.widths(), projected.normals_used(),
          projected.normals_turned(), projected.file_normals_off(), std::size_t(projected.normals_without_direction()),
          projected.outliers().set_aside, "tile by tile: " + tiles_text(tiles), projected.points_per_rank()};
}

void run_project(const ProjectOptions& o) {
  const auto start = std::chrono::steady_clock::now();
  OutputSet outputs({o.input}, {o.output, o.compute.stats_path});
  const Backend backend = start_compute(o.compute);
  Stats stats;
  const MemoryCosts& costs = o.surface.surface.surface == "mls" ? kProjectCosts : kProjectCostsWithNormals;
  ProjectionParams params;
  ProjectRun run;
  const MemoryPlan plan = in_tiles_or_core(
      o.input, o.memory, costs, stats,
      [&](const MemoryPlan& tiles) { run = project_in_tiles(o, tiles, backend, stats, params); },
      [&] { run = project_in_core(o, backend, stats, params); });
  const double total = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  stats.add_time("total", total);

  const double projection_s = stats.time("projection");
  const auto& c = run.counts;
  const std::string ranks = rank_count() > 1 ? "; " + std::to_string(rank_count()) + " ranks" : "";
  std::printf("projected %llu points onto the PSS in %.3f s (projection %.3f s, %.0f points/s, %s backend, %s; %s%s)\n",
              (unsigned long long)run.points, total, projection_s, double(run.points) / projection_s,
              backend_name(backend), threads_text().c_str(), run.memory.c_str(), ranks.c_str());
  std::printf("%s surface%s, h = %g (%s), rho = %g, plane fit %s; converged %lld, not converged %lld, too few "
              "neighbours %lld, degenerate normal %lld; %lld outliers set aside (projected, not samples)\n",
              surface_name(params.surface), normals_text(run.normals), params.h,
              support_text(params.support, run.widths).c_str(), params.rho, o.method.c_str(), (long long)c.converged,
              (long long)c.not_converged, (long long)c.too_few_neighbours, (long long)c.degenerate_normal,
              (long long)run.set_aside);
  print_normals_turned(run.normals_turned, std::size_t(run.points));
  print_file_normals_off(run.file_normals_off, std::size_t(run.points));
  print_file_normals_left_out(run.normals_without_direction, std::size_t(run.points));

  if (!o.compute.stats_path.empty()) {
    auto& v = stats.values();
    record_cloud_run(stats, "project", o.input, o.output, run.points, run.origin, backend);
    record_cloud_surface(stats, params, run.widths, run.normals, run.normals_turned, run.file_normals_off,
                         run.set_aside);
    v["params"]["plane_fit"] = o.method;
    v["params"]["t_tolerance"] = params.t_tolerance;
    record_status_counts(stats, c);
    v["points_per_second"] = double(run.points) / projection_s;
    v["memory"] = {{"budget", plan.budget}, {"tiled", plan.tiled}};
    if (plan.tiled) v["memory"]["points_per_tile"] = plan.points_per_tile;
    v["ranks"] = rank_count();
    v["points_per_rank"] = run.points_per_rank;
    stats.write(o.compute.stats_path);
  }
  outputs.commit();
  std::printf("wrote %s\n", o.output.c_str());
  if (!o.compute.stats_path.empty()) std::printf("wrote %s\n", o.compute.stats_path.c_str());
}

}  // namespace

void add_project_command(CLI::App& app, Action action) {
  auto* command = app.add_subcommand("project", "Move every point onto the point set surface (MLS projection): .ply, .xyz");
  auto o = std::make_shared<ProjectOptions>();
  command->add_option("file", o->input, kCloudFormatsHelp)->required();
  command
      ->add_option("-o,--output", o->output,
                   "output points, by extension: .ply (binary: x y z nx ny nz, red green blue when the input has "
                   "colours, the input PLY's other scalar properties in their types (an input 'status' written as "
                   "input_status), and an int 'status' per point: 0 "
                   "converged, 1 not converged within --iterations, 2 too few neighbours within rho (point and "
                   "normal unchanged), 3 degenerate normal (neighbours on a line)) or .xyz (text: x y z nx ny nz, no "
                   "colours, scalars or status)")
      ->required()
      ->check(points_output());
  add_cloud_surface_flags(*command, o->surface);
  command->add_option("--method", o->method,
                      "plane fit: mls (Eq. 2, default) or wls (Eq. 1); with --surface apss or rimls, mls moves the "
                      "fit to the projected point up to --iterations times, wls fits once at the point")
      ->check(CLI::IsMember({"mls", "wls"}))
      ->capture_default_str();
  add_compute_options(*command, o->compute);
  add_memory_option(*command, o->memory, "the same points (docs/architecture.md says what differs)");
  command->callback([o, action] {
    if (action == Action::run) run_project(*o);
  });
}

}  // namespace pss::app
