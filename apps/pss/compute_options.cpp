#include "commands.hpp"

#include "numbers.hpp"
#include "pss/core/error.hpp"

namespace pss::app {

void add_compute_options(CLI::App& command, ComputeOptions& options) {
  command.add_option("--backend", options.backend, "cpu, cuda, or auto (CUDA when built with it and a GPU is present)")
      ->check(CLI::IsMember({"cpu", "cuda", "auto"}))
      ->capture_default_str();
  // Each OpenMP thread is a system thread with its own stack: 100000 of them exhaust
  // libgomp's stacks and crash. More threads than cores only add overhead, and 1024 is
  // more than the cores of any one shared-memory machine pss runs on.
  command.add_option("--threads", options.threads, "CPU threads (default: all cores)")
      ->check(finite_range(1, kMaxThreads));
  command.add_option("--stats", options.stats_path, "write timings per phase and run parameters as JSON");
}

SpacingEstimate estimate_spacing_of(const PointCloud& cloud, const std::string& file) {
  try {
    return estimate_spacing(cloud.positions);
  } catch (const Error& e) {
    throw file_error(file, e.what());
  }
}

}  // namespace pss::app
