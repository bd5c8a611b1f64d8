#include "commands.hpp"

namespace pss::app {

void add_compute_options(CLI::App& command, ComputeOptions& options) {
  command.add_option("--backend", options.backend, "cpu, cuda, or auto (CUDA when built with it and a GPU is present)")
      ->check(CLI::IsMember({"cpu", "cuda", "auto"}))
      ->capture_default_str();
  command.add_option("--threads", options.threads, "CPU threads (default: all cores)")->check(CLI::NonNegativeNumber);
  command.add_option("--stats", options.stats_path, "write timings per phase and run parameters as JSON");
}

}  // namespace pss::app
