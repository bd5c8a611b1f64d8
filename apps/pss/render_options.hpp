// The options `pss render` and `pss volume` share: image size, camera, secondary rays,
// shading, the --hits and --stats outputs, and the compute backend. Values are checked
// while parsing, so a bad one is a one-line usage error before any work or output.
#pragma once

#include <string>

#include "commands.hpp"
#include "pss/render/camera.hpp"
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

// Throws file_error for an output whose directory does not exist, so that nothing is
// computed, and nothing written, for a run that could not save its results.
void check_output_paths(const RenderOptions& options);

// The shading and secondary-ray settings of the options for this camera.
TraceSettings trace_settings(const RenderOptions& options, const Camera& camera);

}  // namespace pss::app
