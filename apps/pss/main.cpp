// pss: extract and render point set surfaces (Hardware-accelerated Extraction and Rendering
// of Point Set Surfaces, §3–§5) on CPUs and GPUs.
#include <csignal>
#include <cstdio>
#if defined(__GLIBC__)
#include <malloc.h>
#endif
#include <exception>
#include <new>

#include "commands.hpp"
#include "pss/core/error.hpp"
#include "ranks/ranks.hpp"
#include "view/view_command.hpp"

int main(int argc, char** argv) {
#if defined(__GLIBC__)
  // Every array of a quarter MiB or more in a mapping of its own, given back when freed. By
  // default glibc raises that threshold to the largest array freed so far, and the heap then
  // keeps what one phase freed through the next: 60 MB more at 10^6 points (issue 28).
  mallopt(M_MMAP_THRESHOLD, 256 * 1024);
#endif
  // Past a file-size limit (ulimit -f) a write fails with EFBIG, an error that names the file
  // and removes what was written, instead of a signal that kills pss with its files half written.
  std::signal(SIGXFSZ, SIG_IGN);
  // A closed pipe (pss info … | head) makes a write fail instead of killing pss with its
  // scratch files left behind.
  std::signal(SIGPIPE, SIG_IGN);
  // Under mpirun, ranks other than 0 work on rank 0's tiles (ranks/ranks.hpp).
  pss::app::RankSession ranks(argc, argv);
  if (ranks.serves()) return ranks.serve();
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
