// The options `pss render` and `pss volume` share: image size, camera, secondary rays,
// shading, the --hits and --stats outputs, and the compute backend. Values are checked
// while parsing, so a bad one is a one-line usage error before any work or output.
#pragma once

#include <string>

#include "commands.hpp"
#include "pss/backend/backend.hpp"
#include "pss/core/stats.hpp"
#include "pss/render/camera.hpp"
#include "pss/render/rendered_frame.hpp"
#include "pss/render/trace.hpp"

namespace pss::app {

struct RenderOptions {
  std::string output;     // -o, the PNG
  std::string hits_path;  // --hits FILE.ply
  CameraSettings camera;  // --size, --view, --fov
  bool shadows = false;
  bool reflections = false;
  float reflectivity = ShadingParams{}.reflectivity;
  ComputeOptions compute;  // --backend, --threads, --stats
};

void add_render_options(CLI::App& command, RenderOptions& options);

// The shading and secondary-ray settings of the options for this camera.
TraceSettings trace_settings(const RenderOptions& options, const Camera& camera);

// What both commands do with a finished frame. The frame's seconds are the paper's
// per-frame work: primary + secondary + shading.
double frame_seconds(const Stats& stats);
// The PNG and --hits, each written atomically.
void write_frame_outputs(const RenderOptions& options, const RenderedFrame& frame);
// "wrote FILE" for each output, --stats included.
void print_written(const RenderOptions& options);
// The --stats values both commands record; each adds its own before stats.write().
void record_render_stats(Stats& stats, const RenderOptions& options, const RenderedFrame& frame,
                         const TraceSettings& settings, Backend backend, const char* command,
                         const std::string& input);

}  // namespace pss::app
