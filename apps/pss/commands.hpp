// The subcommands of `pss`. Each file adds one to the app and runs it when chosen.
#pragma once

#include <CLI/CLI.hpp>
#include <string>

#include "pss/points/cloud.hpp"
#include "pss/points/spacing.hpp"

namespace pss::app {

// Options every compute subcommand shares.
struct ComputeOptions {
  std::string backend = "auto";
  int threads = 0;
  std::string stats_path;
};
void add_compute_options(CLI::App& command, ComputeOptions& options);

// estimate_spacing of a cloud read from `file`, its errors ("the points coincide") naming
// the file.
SpacingEstimate estimate_spacing_of(const PointCloud& cloud, const std::string& file);

void add_info_command(CLI::App& app);
void add_project_command(CLI::App& app);
void add_render_command(CLI::App& app);
void add_volume_command(CLI::App& app);
void add_extract_command(CLI::App& app);

}  // namespace pss::app
