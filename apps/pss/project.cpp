// pss project FILE -o OUT.ply|.xyz: every point moved onto the PSS, with its normal and, in a
// PLY, the input's colours and scalars and how its projection ended.
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <utility>
#include <vector>

#include "commands.hpp"
#include "numbers.hpp"
#include "output_options.hpp"
#include "pss/core/error.hpp"
#include "pss/io/output_file.hpp"
#include "pss/io/point_cloud_file.hpp"
#include "pss/points/project_cloud.hpp"

namespace pss::app {

namespace {

struct ProjectOptions {
  std::string input, output;
  std::string method = "mls";
  CloudSurfaceFlags surface;
  ComputeOptions compute;
};

void run_project(const ProjectOptions& o) {
  const auto start = std::chrono::steady_clock::now();
  OutputSet outputs({o.input}, {o.output, o.compute.stats_path});
  const Backend backend = start_compute(o.compute);
  Stats stats;
  PointCloud cloud = read_cloud(o.input, stats);
  const ProjectionParams params = projection_params(
      o.surface, cloud, o.input, o.method == "wls" ? PlaneFitMethod::wls : PlaneFitMethod::mls, stats);

  // The input's arrays become the output's (issue 28).
  const CloudProjection result = project_cloud(std::move(cloud), params, backend, stats);
  const PointCloud& projected = result.cloud;
  try {
    check_some_projected(result, params);
  } catch (const Error& e) {
    throw file_error(o.input, e.what());
  }
  {
    ScopedPhase phase(stats, "write");
    std::vector<std::int32_t> status(result.status.size());
    for (std::size_t i = 0; i < status.size(); ++i) status[i] = std::int32_t(result.status[i]);
    const PlyIntProperty extra[] = {{"status", status}};
    write_point_cloud(o.output, result.cloud, extra);
  }
  const double total = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  stats.add_time("total", total);

  const double projection_s = stats.time("projection");
  const auto& c = result.counts;
  std::printf("projected %zu points onto the PSS in %.3f s (projection %.3f s, %.0f points/s, %s backend, %d threads)\n",
              projected.size(), total, projection_s, double(projected.size()) / projection_s, backend_name(backend),
              cpu_threads());
  std::printf("%s surface%s, h = %g (%s), rho = %g, plane fit %s; converged %lld, not converged %lld, too few "
              "neighbours %lld, degenerate normal %lld; %lld outliers set aside (projected, not samples)\n",
              surface_name(params.surface), normals_text(result.normals), params.h,
              support_text(params.support, result.widths).c_str(), params.rho, o.method.c_str(), (long long)c.converged,
              (long long)c.not_converged, (long long)c.too_few_neighbours, (long long)c.degenerate_normal,
              (long long)result.outliers.set_aside);
  print_normals_turned(result.normals_turned, projected.size());

  if (!o.compute.stats_path.empty()) {
    auto& v = stats.values();
    record_cloud_run(stats, "project", o.input, o.output, projected, backend);
    v["params"] = {{"h", params.h}, {"rho", params.rho}, {"plane_fit", o.method},
                   {"support", support_name(params.support)},
                   {"surface", surface_name(params.surface)}, {"normals", normals_used_name(result.normals)},
                   {"outliers", o.surface.surface.outliers},
                   {"h_least", result.widths.least}, {"h_largest", result.widths.largest},
                   {"max_mls_iterations", params.max_mls_iterations}, {"t_tolerance", params.t_tolerance}};
    v["status"] = {{"converged", c.converged}, {"not_converged", c.not_converged},
                   {"too_few_neighbours", c.too_few_neighbours}, {"degenerate_normal", c.degenerate_normal}};
    v["outliers_set_aside"] = result.outliers.set_aside;
    v["normals_turned"] = result.normals_turned;
    v["points_per_second"] = double(projected.size()) / projection_s;
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
  command->add_option("file", o->input, "point cloud (.ply, .xyz/.txt/.pts, .obj, .stl, .pcd, .las)")->required();
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
  command->callback([o, action] {
    if (action == Action::run) run_project(*o);
  });
}

}  // namespace pss::app
