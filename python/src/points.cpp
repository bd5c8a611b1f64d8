#include "points.hpp"

#include <string>
#include <utility>

#include "arrays.hpp"
#include "frame.hpp"
#include "interruptible.hpp"
#include "options.hpp"
#include "pss/core/error.hpp"
#include "pss/io/point_cloud_file.hpp"
#include "pss/mesh/mesh_cloud.hpp"
#include "pss/mesh/mesh_stats.hpp"
#include "pss/points/project_cloud.hpp"
#include "pss/points/render_cloud.hpp"
#include "pss/points/surface_stats.hpp"
#include "pss/points/spacing.hpp"

namespace pss::python {

namespace {

// The points, and normals when given (their count the points'); colours are the caller's.
PointCloud cloud_of(const py::handle& points, const py::object& normals) {
  PointCloud cloud = cloud_of_rows(points, "points");
  if (!normals.is_none()) {
    cloud.normals = vec3_rows(normals, "normals");
    if (cloud.normals.size() != cloud.positions.size())
      throw Error("normals: expected one per point (" + std::to_string(cloud.positions.size()) + "), got " +
                  std::to_string(cloud.normals.size()));
    tidy_normals(cloud);
  }
  return cloud;
}

// The h of `pss info` (and of the CLI when --h is not given); problems name the points.
template <class Estimate>
float h_from_spacing(const std::vector<vec3>& points, Estimate estimate) {
  try {
    return float(estimate(points));
  } catch (const Error& e) {
    throw Error(std::string("points: ") + e.what());
  }
}

float suggested_h(const std::vector<vec3>& p) {
  return h_from_spacing(p, [](const auto& q) { return estimate_spacing(q).suggested_h; });
}

// support=None: adaptive, unless h fixes one width for every sample (as the CLI's --support).
Support support_of(const py::dict& o, bool h_given) {
  if (!is_given(o, "support")) return default_support(h_given);
  return choice(o, "support", {"adaptive", "global"}) == "global" ? Support::global : Support::adaptive;
}

SurfaceOperator surface_of(const py::dict& o) {
  return surface_operator_of(choice(o, "surface", {"mls", "apss", "rimls"}));
}

OutlierPolicy outliers_of(const py::dict& o) {
  return choice(o, "outliers", {"set-aside", "keep"}) == "keep" ? OutlierPolicy::keep : OutlierPolicy::set_aside;
}

float estimate_h(const py::handle& points) {
  const PointCloud cloud = cloud_of_rows(points, "points");
  py::gil_scoped_release release;
  return suggested_h(cloud.positions);
}

// The keyword arguments of a cloud's PSS that project and mesh share (the CLI's
// CloudSurfaceFlags), read with the GIL held, and the projection's parameters they give, h
// from the spacing where None (run without the GIL).
struct CloudSurfaceArgs {
  std::optional<float> h, rho;
  std::optional<int> iterations;  // none: default_iterations of the surface
  Support support;
  SurfaceOperator surface;
  OutlierPolicy outliers;

  explicit CloudSurfaceArgs(const py::dict& o)
      : h(positive_or_none(o, "h")),
        rho(positive_or_none(o, "rho")),
        iterations(is_given(o, "iterations") ? std::optional<int>(integer_in(o, "iterations", 1, 100)) : std::nullopt),
        support(support_of(o, h.has_value())),
        surface(surface_of(o)),
        outliers(outliers_of(o)) {}

  ProjectionParams params(const PointCloud& cloud, PlaneFitMethod plane) const {
    ProjectionParams p = ProjectionParams::from_h(h ? *h : suggested_h(cloud.positions), plane);
    if (rho) p.rho = *rho;
    p.support = support;
    p.surface = surface;
    p.outliers = outliers;
    p.max_mls_iterations = iterations ? *iterations : default_iterations(surface);
    return p;
  }
};

py::tuple project(const py::handle& points, const py::dict& o) {
  PointCloud cloud = cloud_of(points, option(o, "normals"));
  const PlaneFitMethod plane = choice(o, "method", {"mls", "wls"}) == "wls" ? PlaneFitMethod::wls : PlaneFitMethod::mls;
  const CloudSurfaceArgs args(o);
  const Backend backend = backend_of(o);
  const bool full_output = flag(o, "full_output");
  Stats stats;
  CloudProjection result = run_interruptibly([&] {
    const ProjectionParams params = args.params(cloud, plane);
    CloudProjection projection = project_cloud(std::move(cloud), params, backend, stats);  // no second copy
    check_some_projected(projection.counts, params);
    record_cloud_surface(stats, params, projection.widths, projection.normals, projection.normals_turned,
                         projection.file_normals_off, projection.outliers.set_aside);
    record_status_counts(stats, projection.counts);
    stats.values()["backend"] = backend_name(backend);
    return projection;
  });
  std::vector<std::int32_t> status(result.status.size());
  for (std::size_t i = 0; i < status.size(); ++i) status[i] = std::int32_t(result.status[i]);
  const auto n = py::ssize_t(status.size());
  py::object positions = world_numpy(std::move(result.cloud.positions), result.cloud.origin, {n, 3});
  py::object normals = to_numpy(std::move(result.cloud.normals));
  py::object statuses = to_numpy<std::int32_t>(std::move(status), {n});
  if (!full_output) return py::make_tuple(positions, normals, statuses);
  return py::make_tuple(positions, normals, statuses, stats_dict(stats));
}

py::tuple mesh(const py::handle& points, const py::dict& o) {
  const PointCloud cloud = cloud_of(points, option(o, "normals"));
  const CloudSurfaceArgs args(o);
  const std::optional<float> cell = positive_or_none(o, "cell");
  const auto crease_angle = float(number_in(o, "crease_angle", 0, 180, true));
  const std::optional<BorderMode> borders = border_choice_of(choice(o, "borders", {"auto", "clip", "extend"}));
  const Backend backend = backend_of(o);
  const bool full_output = flag(o, "full_output");
  Stats stats;
  CloudMesh result = run_interruptibly([&] {
    if (cloud.size() < 3) throw Error("points: a mesh needs at least 3 (got " + std::to_string(cloud.size()) + ")");
    MeshParams params;
    params.projection = args.params(cloud, PlaneFitMethod::mls);
    params.projection.borders = borders_for(borders, cloud);
    if (cell) params.cell = *cell;
    params.crease_angle = crease_angle;
    CloudMesh made = mesh_cloud(cloud, params, backend, stats);
    record_cloud_mesh(stats, made, params, topology(made.mesh));
    stats.values()["backend"] = backend_name(backend);
    return made;
  });
  const auto v = py::ssize_t(result.mesh.positions.size()), t = py::ssize_t(result.mesh.triangles.size());
  py::object vertices = world_numpy(std::move(result.mesh.positions), cloud.origin, {v, 3});
  py::object normals = to_numpy(std::move(result.mesh.normals));
  py::object faces = to_numpy<std::int32_t>(std::move(result.mesh.triangles), {t, 3});
  if (!full_output) return py::make_tuple(vertices, normals, faces);
  return py::make_tuple(vertices, normals, faces, stats_dict(stats));
}

py::object render(const py::handle& points, const py::dict& o) {
  PointCloud cloud = cloud_of(points, option(o, "normals"));
  if (cloud.size() == 0) throw Error("points: there are none to render");
  if (is_given(o, "colors")) {
    cloud.colors = rgb8_rows(option(o, "colors"), "colors");
    if (cloud.colors.size() != cloud.size())
      throw Error("colors: expected one per point (" + std::to_string(cloud.size()) + "), got " +
                  std::to_string(cloud.colors.size()));
  }
  const std::optional<float> h = positive_or_none(o, "h"), rho = positive_or_none(o, "rho"),
                             b = positive_or_none(o, "b"), epsilon = positive_or_none(o, "epsilon");
  const py::object iterations = option(o, "iterations");
  const int max_iterations = py::isinstance<py::str>(iterations) && iterations.cast<std::string>() == "auto"
                                 ? kAutoIterations
                                 : integer_in(o, "iterations", 1, kAutoIterations);
  const int candidates = integer_in(o, "candidates", 1, kMaxCandidates);
  const SecondaryMode secondary =
      choice(o, "secondary", {"full", "paper"}) == "paper" ? SecondaryMode::paper : SecondaryMode::full;
  const std::optional<BorderMode> chosen_borders = border_choice_of(choice(o, "borders", {"auto", "clip", "extend"}));
  const std::optional<float> spacing = is_given(o, "ball_spacing")
                                           ? std::optional<float>(float(number_in(o, "ball_spacing", 0, 1e30)))
                                           : std::nullopt;
  const Support support = support_of(o, h.has_value());
  const SurfaceOperator surface = surface_of(o);
  const OutlierPolicy outliers = outliers_of(o);
  const Backend backend = backend_of(o);
  const FrameRequest request = frame_request(o);
  const Camera camera = make_camera(request, cloud.bounds(), cloud.origin);
  const TraceSettings settings = trace_settings(request, camera);

  Stats stats;
  RenderedFrame frame = run_interruptibly([&] {
    RayPssParams params = RayPssParams::from_h(
        h ? *h : h_from_spacing(cloud.positions, [](const auto& q) { return default_h(q); }));
    if (rho) params.projection.rho = *rho;
    params.projection.support = support;
    params.projection.surface = surface;
    params.projection.outliers = outliers;
    if (b) params.ball_radius = *b;
    params.ball_spacing = spacing ? *spacing : 0.5f * params.ball_radius;
    if (epsilon) params.epsilon = *epsilon;
    params.max_iterations = max_iterations;
    params.max_candidates = candidates;
    params.secondary = secondary;
    params.projection.borders = borders_for(chosen_borders, cloud);
    validate(params);
    const PreparedCloud prepared(cloud, params, backend, stats,
                                 cloud.has_colors() ? SurfaceColor::samples : SurfaceColor::albedo);
    check_some_surface(prepared, params);
    stats.values()["local_polynomials"] = prepared.locals().size();
    stats.values()["outliers_set_aside"] = prepared.outliers().set_aside;
    stats.values()["points_merged"] = prepared.widths().merged_count;
    stats.values()["normals_turned"] = prepared.normals_turned();
    stats.values()["file_normals_off"] = prepared.file_normals_off();
    stats.values()["params"] = {{"h", params.projection.h}, {"rho", params.projection.rho}, {"b", params.ball_radius},
                                {"support", support_name(support)}, {"surface", surface_name(surface)},
                                {"normals", normals_used_name(prepared.normals_used())},
                                {"h_least", prepared.widths().least}, {"h_largest", prepared.widths().largest},
                                {"ball_spacing", params.ball_spacing}, {"epsilon", params.epsilon},
                                {"iterations", params.max_iterations}, {"max_candidates", params.max_candidates},
                                {"borders", border_name(params.projection.borders)}};
    return render_cloud(prepared, camera, settings, backend, stats);
  });
  stats.values()["backend"] = backend_name(backend);
  return frame_result(std::move(frame), stats, request);
}

py::tuple read_points(const std::string& path) {
  PointCloud cloud;
  {
    py::gil_scoped_release release;
    cloud = read_point_cloud(path);
  }
  py::object normals = py::none(), colors = py::none();
  if (cloud.has_normals()) normals = to_numpy(std::move(cloud.normals));
  if (cloud.has_colors()) colors = to_numpy(std::move(cloud.colors));
  const auto n = py::ssize_t(cloud.size());
  return py::make_tuple(world_numpy(std::move(cloud.positions), cloud.origin, {n, 3}), normals, colors);
}

}  // namespace

void bind_points(py::module_& m) {
  m.def("estimate_h", &estimate_h, py::arg("points"));
  m.def("project", &project, py::arg("points"), py::arg("options"));
  m.def("mesh", &mesh, py::arg("points"), py::arg("options"));
  m.def("render", &render, py::arg("points"), py::arg("options"));
  m.def("read_points", &read_points, py::arg("path"));
}

}  // namespace pss::python
