// pss volume FILE (--iso V | --gradient) -o OUT.png|.jpg|.exr: the PSS of a volume, extracted and
// rendered along every primary ray by the predictor-corrector method (§4, §5.1).
#include <chrono>
#include <cstdio>

#include "commands.hpp"
#include "pss/io/output_file.hpp"
#include "pss/render/frame_outputs.hpp"
#include "render_options.hpp"
#include "volume_options.hpp"

namespace pss::app {

namespace {

struct VolumeCommandOptions {
  VolumeOptions volume;
  bool debug_projection = false;
  RenderOptions render;
};

void run_volume(const VolumeCommandOptions& o) {
  const auto start = std::chrono::steady_clock::now();
  OutputSet outputs({o.volume.input, o.render.camera_file}, {o.render.output, o.render.hits_path, o.render.compute.stats_path});
  const Backend backend = start_compute(o.render.compute);
  Stats stats;
  PreparedVolume volume = load_volume(o.volume, stats);
  volume.params.debug_projection = o.debug_projection;
  const Camera camera = make_camera(o.render, volume.surface_bounds(), glm::dvec3(0.0));
  const TraceSettings settings = trace_settings(o.render, camera);
  const SceneMirror scene(backend, volume);  // uploaded once for all --frames
  RenderedFrame frame =
      render_frames(o.render, stats, [&](Stats& s) { return render_volume(scene, camera, settings, backend, s); });
  if (o.debug_projection) paint_debug_projection(frame);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  stats.add_time("total", seconds);
  const double frame_s = frame_seconds(stats);
  write_frame_outputs(o.render, frame);

  const FrameSummary s = summarize(frame);
  const VolumeView v = volume.fields.volume.view();
  std::printf("rendered %s (%dx%dx%d) at %dx%d in %.3f s: frame %.3f s (%.2f fps), gradients %.3f s "
              "(%s backend, %s)\n", o.volume.input.c_str(), v.dims.x, v.dims.y, v.dims.z, camera.width,
              camera.height, seconds, frame_s, 1.0 / frame_s, stats.time("gradients"), backend_name(backend),
              threads_text().c_str());
  std::printf("%s, %lld hits of %lld rays, %.2f projections per hit; h = %g, b = %g, eps = %g, bricks %lld/%zu\n",
              o.volume.method.c_str(), (long long)s.hits, (long long)s.rays, s.mean_iterations, volume.params.h,
              volume.params.step, volume.params.epsilon, (long long)volume.bricks.occupied_count,
              volume.bricks.occupied.size());

  if (!o.render.compute.stats_path.empty()) {
    record_render_stats(stats, o.render, frame, settings, backend, "volume", o.volume.input);
    auto& j = stats.values();
    j["debug_projection"] = o.debug_projection;
    j["volume"] = describe(volume, o.volume);
    stats.write(o.render.compute.stats_path);
  }
  outputs.commit();
  print_written(o.render);
  if (s.hits == 0)
    std::fprintf(stderr, "pss volume: no ray hit the surface of %s (%lld cells cross it)\n", o.volume.input.c_str(),
                 (long long)volume.cells.crossed_count);
}

}  // namespace

void add_volume_command(CLI::App& app, Action action) {
  auto* command = app.add_subcommand("volume", "Extract and render the PSS of a volume to an image: .png, .jpg, .exr (paper 4, 5.1)");
  auto o = std::make_shared<VolumeCommandOptions>();
  add_volume_options(*command, o->volume, true);
  command->add_flag("--debug-projection", o->debug_projection,
                    "the paper's Figure 2: red where the predictor moved the ray's first sample farther than "
                    "epsilon, green where the corrector still did");
  add_render_options(*command, o->render);
  command->callback([o, action] {
    check_render_options(o->render);
    if (action == Action::run) run_volume(*o);
    else check_volume_options(o->volume);
  });
}

}  // namespace pss::app
