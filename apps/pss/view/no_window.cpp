// `pss view` in a build without GLFW and Dear ImGui: --headless only (headless.cpp).
#include <cstdio>

#include "viewer.hpp"

namespace pss::app::view {

bool has_window() { return false; }

int run_viewer(const ViewerOptions&) {
  std::fprintf(stderr,
               "pss view: error: this build of pss has no window (GLFW, OpenGL or Dear ImGui was missing when it was "
               "built): use --headless with --script\n");
  return 1;
}

}  // namespace pss::app::view
