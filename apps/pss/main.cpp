// pss: extract and render point set surfaces (Hardware-accelerated Extraction and Rendering
// of Point Set Surfaces, §3–§5) on CPUs and GPUs.
#include <cstdio>
#include <exception>
#include <new>

#include "commands.hpp"
#include "pss/core/error.hpp"

int main(int argc, char** argv) {
  CLI::App app{"pss: point set surfaces of point clouds and volumes, on CPUs and GPUs"};
  app.require_subcommand(1, 1);
  app.set_version_flag("--version", "pss 0.1.0");
  pss::app::add_info_command(app);
  pss::app::add_project_command(app);
  pss::app::add_render_command(app);
  pss::app::add_volume_command(app);
  pss::app::add_extract_command(app);

  // Usage errors: one line naming the subcommand, then exit 2 (help and --version exit 0).
  app.failure_message([](const CLI::App* top, const CLI::Error& e) {
    std::string name = "pss";
    for (const CLI::App* sub : top->get_subcommands()) name += " " + sub->get_name();
    // CLI11 echoes what it refuses (an unknown flag, a value not among the choices) as given.
    return name + ": error: " + pss::one_line(e.what()) + " (see --help)\n";
  });
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;
  } catch (const pss::Error& e) {
    std::fprintf(stderr, "pss: error: %s\n", pss::one_line(e.what()).c_str());
    return 1;
  } catch (const std::bad_alloc&) {
    // Sizes are checked where they are read; what is left is a machine with too little memory.
    std::fprintf(stderr, "pss: error: out of memory\n");
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "pss: internal error: %s\n", e.what());
    return 1;
  }
  return 0;
}
