// pss: extract and render point set surfaces (Hardware-accelerated Extraction and Rendering
// of Point Set Surfaces, §3–§5) on CPUs and GPUs.
#include <cstdio>
#include <exception>
#include <new>

#include "commands.hpp"
#include "pss/core/error.hpp"
#include "view/view_command.hpp"

int main(int argc, char** argv) {
  CLI::App app{"pss: point set surfaces of point clouds and volumes, on CPUs and GPUs"};
  pss::app::configure_app(app, pss::app::Action::run);
  pss::app::add_view_command(app);
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
