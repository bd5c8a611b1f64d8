// `pss view`: a window in builds with GLFW and Dear ImGui (apps/pss/CMakeLists.txt), and
// --headless in every build.
#pragma once

#include <CLI/CLI.hpp>

namespace pss::app {

void add_view_command(CLI::App& app);

}  // namespace pss::app
