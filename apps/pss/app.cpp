#include "commands.hpp"

#include "pss/core/text.hpp"

namespace pss::app {

void configure_app(CLI::App& app, Action action) {
  app.require_subcommand(1, 1);
  app.set_version_flag("--version", "pss 0.1.0");
  add_info_command(app, action);
  add_project_command(app, action);
  add_mesh_command(app, action);
  add_render_command(app, action);
  add_volume_command(app, action);
  add_extract_command(app, action);

  // Usage errors: one line naming the subcommand, then exit 2 (help and --version exit 0).
  app.failure_message([](const CLI::App* top, const CLI::Error& e) {
    std::string name = "pss";
    for (const CLI::App* sub : top->get_subcommands()) name += " " + sub->get_name();
    // CLI11 echoes what it refuses (an unknown flag, a value not among the choices) as given.
    return name + ": error: " + pss::one_line(e.what()) + " (see --help)\n";
  });
}

}  // namespace pss::app
