// pss render FILE -o OUT.png|.jpg|.exr: ray tracing the point set surface of a point cloud (§5.2).
#include <chrono>
#include <cstdio>
#include <cfloat>

#include "commands.hpp"
#include "numbers.hpp"
#include "pss/core/error.hpp"
#include "pss/io/output_file.hpp"
#include "pss/io/point_cloud_file.hpp"
#include "pss/points/render_cloud.hpp"
#include "pss/points/spacing.hpp"
#include "pss/render/frame_outputs.hpp"
#include "render_options.hpp"

namespace pss::app {

namespace {

struct RenderCloudOptions {
  std::string input;
  float h = 0, rho = 0, b = 0, epsilon = 0;
  float ball_spacing = -1;  // -1: b/2
  std::string iterations = "2";
  int candidates = RayPssParams::from_h(1).max_candidates;
  std::string secondary = "full";
  std::string borders = "auto";
  std::string support;  // empty: support_of's default
  SurfaceOptions surface;
  bool color = false;  // shade with the samples' colours
  RenderOptions render;
};

int iterations_of(const std::string& text) { return text == "auto" ? kAutoIterations : std::stoi(text); }

void run_render(const RenderCloudOptions& o) {
  const auto start = std::chrono::steady_clock::now();
  OutputSet outputs({o.input, o.render.camera_file}, {o.render.output, o.render.hits_path, o.render.compute.stats_path});
  const Backend backend = start_compute(o.render.compute);
  Stats stats;
  PointCloud cloud;
  {
    ScopedPhase phase(stats, "read");
    cloud = read_point_cloud(o.input);
  }
  if (cloud.size() == 0) throw file_error(o.input, "has no points");
  if (o.color && !cloud.has_colors())
    throw file_error(o.input, "has no per-point colours (--color needs red, green, blue)");
  float h = o.h;
  if (h == 0) {
    check_enough_for_default_h(cloud.size(), o.input);
    ScopedPhase phase(stats, "estimate h");
    h = naming_input(o.input, [&] { return default_h(cloud.positions); });
  }
  RayPssParams params = RayPssParams::from_h(h);
  if (o.rho != 0) params.projection.rho = o.rho;
  params.projection.support = support_of(o.support, o.h != 0);
  apply_surface_options(o.surface, params.projection);
  if (o.b != 0) params.ball_radius = o.b;
  params.ball_spacing = o.ball_spacing >= 0 ? o.ball_spacing : 0.5f * params.ball_radius;
  if (o.epsilon != 0) params.epsilon = o.epsilon;
  params.max_iterations = iterations_of(o.iterations);
  params.max_candidates = o.candidates;
  params.secondary = o.secondary == "paper" ? SecondaryMode::paper : SecondaryMode::full;
  params.projection.borders = borders_for(border_choice_of(o.borders), cloud);
  validate(params);

  const Camera camera = make_camera(o.render, cloud.bounds(), cloud.origin);
  const TraceSettings settings = trace_settings(o.render, camera);
  // What the cloud cannot give (a neighbourhood wider than it, no surface) names it.
  const PreparedCloud prepared = naming_input(o.input, [&] {
    return PreparedCloud(cloud, params, backend, stats, o.color ? SurfaceColor::samples : SurfaceColor::albedo);
  });
  naming_input(o.input, [&] { check_some_surface(prepared, params); });
  const RenderedFrame frame =
      render_frames(o.render, stats, [&](Stats& s) { return render_cloud(prepared, camera, settings, backend, s); });
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  stats.add_time("total", seconds);
  const double frame_s = frame_seconds(stats);
  write_frame_outputs(o.render, frame);

  const FrameSummary s = summarize(frame);
  std::printf("rendered %s (%zu points) at %dx%d in %.3f s: frame %.3f s (%.2f fps), preprocess %.3f s, "
              "BVH %.3f s (%s backend, %s)\n", o.input.c_str(), cloud.size(), camera.width, camera.height,
              seconds, frame_s, 1.0 / frame_s, stats.time("preprocess"), stats.time("acceleration structure"),
              backend_name(backend), threads_text().c_str());
  std::printf("%lld rays, %lld hits, %.2f projections per hit, %lld secondary rays; %s surface%s, borders %s, %lld "
              "outliers set aside, h = %g (%s), b = %g, eps = %g\n",
              (long long)s.rays, (long long)s.hits, s.mean_iterations, (long long)s.secondary_rays,
              surface_name(params.projection.surface), normals_text(prepared.normals_used()),
              border_name(params.projection.borders),
              (long long)prepared.outliers().set_aside, params.projection.h,
              support_text(params.projection.support, prepared.widths()).c_str(), params.ball_radius, params.epsilon);
  print_normals_turned(prepared.normals_turned(), cloud.size());
  print_file_normals_off(prepared.file_normals_off(), cloud.size());
  print_file_normals_left_out(file_normals_without_direction(cloud, o.surface), cloud.size());

  if (!o.render.compute.stats_path.empty()) {
    record_render_stats(stats, o.render, frame, settings, backend, "render", o.input);
    auto& v = stats.values();
    v["points"] = cloud.size();
    v["samples_left_out"] = prepared.left_out();
    v["outliers_set_aside"] = prepared.outliers().set_aside;
    v["points_merged"] = prepared.widths().merged_count;
    v["normals_turned"] = prepared.normals_turned();
    v["file_normals_off"] = prepared.file_normals_off();
    v["local_polynomials"] = prepared.locals().size();
    v["params"] = {{"h", params.projection.h}, {"rho", params.projection.rho}, {"b", params.ball_radius},
                   {"support", support_name(params.projection.support)},
                   {"surface", surface_name(params.projection.surface)},
                   {"normals", normals_used_name(prepared.normals_used())}, {"outliers", o.surface.outliers},
                   {"outlier_threshold", prepared.outliers().threshold},
                   {"h_least", prepared.widths().least}, {"h_largest", prepared.widths().largest},
                   {"support_levels", prepared.support_levels()},
                   {"ball_spacing", params.ball_spacing},
                   {"epsilon", params.epsilon}, {"iterations", o.iterations},
                   {"max_candidates", params.max_candidates}, {"secondary", o.secondary},
                   {"borders", border_name(params.projection.borders)},
                   {"secondary_offset", params.secondary_offset}, {"color", o.color}};
    stats.write(o.render.compute.stats_path);
  }
  outputs.commit();
  print_written(o.render);
  if (s.hits == 0)  // an image of the background alone: say so, as pss volume does
    std::fprintf(stderr, "pss render: no ray hit the surface of %s (the camera may look away from it, or b = %g is too "
                 "small for its spacing)\n", o.input.c_str(), params.ball_radius);
}

std::string check_iterations(const std::string& text) {
  if (text == "auto") return {};
  std::size_t used = 0;
  int n = 0;
  try {
    n = std::stoi(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != text.size() || n < 1 || n > kAutoIterations)
    return "expected a number from 1 to " + std::to_string(kAutoIterations) + " or 'auto' (got " + quote(text) + ")";
  return {};
}

}  // namespace

void add_render_command(CLI::App& app, Action action) {
  auto* command = app.add_subcommand("render", "Ray trace the point set surface of a point cloud to an image: .png, .jpg, .exr (paper 5.2)");
  auto o = std::make_shared<RenderCloudOptions>();
  command->add_option("file", o->input, kCloudFormatsHelp)->required();
  command->add_option("--h", o->h, "Gaussian width h (default: estimated from the spacing and the noise, see pss info)")
      ->check(finite_positive());
  command->add_option("--rho", o->rho, "range-query radius of the projection (default 2h; with adaptive support, at h)")
      ->check(finite_positive());
  add_support_option(*command, o->support);
  add_surface_options(*command, o->surface);
  command->add_option("--b", o->b, "ball radius b around each sample's local polynomial (default h, at most rho)")
      ->check(finite_positive());
  command->add_option("--ball-spacing", o->ball_spacing,
                      "keep a local polynomial only where none kept within this distance passes within 0.05 h of its "
                      "sample (default b/2; 0 keeps one per sample, as the paper)")
      ->check(finite_range(0, double(FLT_MAX)));
  command->add_option("--epsilon", o->epsilon, "a candidate is a hit when its projection moves it less (default 1e-3 h)")
      ->check(finite_positive());
  command->add_option("--iterations", o->iterations, "projections per candidate: N, or auto (until |projection - r| < eps)")
      ->check(CLI::Validator(check_iterations, "N|auto", "iterations"))
      ->capture_default_str();
  command->add_option("--candidates", o->candidates,
                      "ball intersections a ray tries before it is a miss: fewer make frames faster on the GPU, "
                      "whose frame lasts as long as its slowest rays, and can miss grazing rays")
      ->check(CLI::Range(1, kMaxCandidates))
      ->capture_default_str();
  command->add_option("--secondary", o->secondary,
                      "secondary rays: full (projected like primary rays) or paper (first local-polynomial hit)")
      ->check(CLI::IsMember({"full", "paper"}))
      ->capture_default_str();
  command->add_option("--borders", o->borders,
                      "where the surface ends: clip (at its samples: no band past an open rim or a thin part's "
                      "edge), extend (as far as the projection reaches, about b past the last samples: the paper), "
                      "or auto (clip for a mesh's vertices, whose surface ends at them; extend for scans)")
      ->check(CLI::IsMember({"auto", "clip", "extend"}))
      ->capture_default_str();
  command->add_flag("--color", o->color,
                    "shade with the points' own colours (the file's red green blue), averaged at each hit with the "
                    "projection's Gaussian weights over the points within rho, in linear light");
  add_render_options(*command, o->render);
  command->callback([o, action] {
    check_render_options(o->render);
    if (action == Action::run) run_render(*o);
  });
}

}  // namespace pss::app
