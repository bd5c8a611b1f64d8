// The options `pss render` and `pss volume` share: image size, camera, secondary rays,
// shading, the --hits and --stats outputs, and the compute backend. Values are checked
// while parsing, so a bad one is a one-line usage error before any work or output.
#pragma once

#include <algorithm>
#include <string>
#include <vector>

#include <glm/ext/vector_double3.hpp>

#include "commands.hpp"
#include "pss/backend/backend.hpp"
#include "pss/core/stats.hpp"
#include "pss/render/camera.hpp"
#include "pss/render/rendered_frame.hpp"
#include "pss/render/trace.hpp"

namespace pss::app {

struct RenderOptions {
  std::string output;     // -o, the image (.png, .jpg, .exr)
  bool transparent = false;  // alpha 0 where the primary ray missed
  std::string hits_path;  // --hits FILE.ply or FILE.xyz
  CameraSettings camera;  // --size, --view, --fov
  std::string camera_file;  // --camera FILE.json, instead of --view and --fov
  bool shadows = false;
  bool reflections = false;
  float reflectivity = ShadingParams{}.reflectivity;
  int frames = 1;          // --frames: the same frame again, as a viewer would draw it
  ComputeOptions compute;  // --backend, --threads, --stats
};

void add_render_options(CLI::App& command, RenderOptions& options);

// What no single flag's validator can see: --transparent with a JPEG -o. Throws CLI11's
// usage error, so it is reported like the others, before any work.
void check_render_options(const RenderOptions& options);

// The camera of --camera, or the default view of `bounds` turned by --view and --fov.
// --look-at and a camera file's eye are in world coordinates; bounds and the camera are
// relative to `origin` (a point cloud's, cloud.hpp).
Camera make_camera(const RenderOptions& options, const Aabb& bounds, const glm::dvec3& origin);

// The shading and secondary-ray settings of the options for this camera.
TraceSettings trace_settings(const RenderOptions& options, const Camera& camera);

// What both commands do with a finished frame. The frame's seconds are the paper's
// per-frame work: primary + secondary + shading.
double frame_seconds(const Stats& stats);

// Renders the frame options.frames times with render(Stats&) and keeps the last. The
// phases go to stats from the median frame: the first frames of a run also pay for the
// GPU's clocks rising and its caches filling, which a viewer drawing frame after frame
// does not. --stats lists every frame's seconds.
template <class Render>
RenderedFrame render_frames(const RenderOptions& options, Stats& stats, Render&& render) {
  std::vector<Stats> runs(std::size_t(options.frames));
  std::vector<double> seconds;
  RenderedFrame frame;
  for (Stats& s : runs) {
    frame = render(s);
    seconds.push_back(frame_seconds(s));
  }
  std::vector<std::size_t> order(runs.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::nth_element(order.begin(), order.begin() + order.size() / 2, order.end(),
                   [&](std::size_t a, std::size_t b) { return seconds[a] < seconds[b]; });
  for (const auto& [phase, s] : runs[order[order.size() / 2]].times()) stats.add_time(phase, s);
  for (const auto& [phase, bytes] : runs[order[order.size() / 2]].peaks()) stats.add_peak(phase, bytes);
  stats.values()["frames"] = options.frames;
  stats.values()["every_frame_seconds"] = seconds;
  return frame;
}

// The image and --hits, each written atomically.
void write_frame_outputs(const RenderOptions& options, const RenderedFrame& frame);
// "wrote FILE" for each output, --stats included.
void print_written(const RenderOptions& options);
// The --stats values both commands record; each adds its own before stats.write().
void record_render_stats(Stats& stats, const RenderOptions& options, const RenderedFrame& frame,
                         const TraceSettings& settings, Backend backend, const char* command,
                         const std::string& input);

}  // namespace pss::app
