// `pss view`: a window (GLFW, OpenGL 3.3 core) showing the PSS of a point cloud or a volume,
// drawn by the render thread (render_thread.hpp) and put on screen as a texture, with a
// Dear ImGui panel for the paper's parameters; or, with --headless, the same session
// (session.hpp) run by its script alone. No rendering code of its own.
#pragma once

#include <string>

#include "orbit.hpp"
#include "scene.hpp"

namespace pss::app::view {

struct ViewerOptions {
  VolumeOptions file;  // the input, its raw-volume flags and the volume settings
  ViewSettings settings;
  Orbit orbit;
  int width = 960, height = 720;  // the window's, which is the full-size frame's
  std::string camera_file;        // --camera: the first view
  std::string script;             // --script: run these steps, then quit
  bool headless = false;          // --headless: no window; the script's steps only
  std::string screenshot_dir = ".";
};

// Opens the window and runs until it is closed or the script ends. A file that cannot be
// read or prepared is shown as a message in the window (and on stderr). Returns the exit
// status: 0, or 1 when the window cannot be opened or a script step cannot be carried out.
// In a build without GLFW and Dear ImGui (has_window() false) it says so and returns 1.
int run_viewer(const ViewerOptions& options);

// Whether this build has the window (viewer.cpp) or not (no_window.cpp).
bool has_window();

// --headless: runs the script's steps (options.script, required) with no window and no
// display, as the window would: the same frames, reduced while a view is new, the same
// screenshots and timings. Returns 0, or 1 when a file or a step cannot be carried out.
int run_headless(const ViewerOptions& options);


}  // namespace pss::app::view
