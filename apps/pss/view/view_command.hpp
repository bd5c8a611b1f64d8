// `pss view`, in builds with GLFW and Dear ImGui (apps/pss/CMakeLists.txt).
#pragma once

#include <CLI/CLI.hpp>

namespace pss::app {

void add_view_command(CLI::App& app);

}  // namespace pss::app
