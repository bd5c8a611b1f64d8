// The subcommands of `pss`. Each file adds one to the app and runs it when chosen.
#pragma once

#include <CLI/CLI.hpp>
#include <string>

#include "pss/points/cloud.hpp"
#include "pss/points/projection.hpp"
#include "pss/points/sample_normals.hpp"
#include "pss/points/spacing.hpp"
#include "pss/points/support.hpp"

namespace pss::app {

// Options every compute subcommand shares.
struct ComputeOptions {
  std::string backend = "auto";
  int threads = 0;
  std::string stats_path;
};
void add_compute_options(CLI::App& command, ComputeOptions& options);  // with --progress
// --progress auto|always|never: sets the process's ProgressMode when given.
void add_progress_option(CLI::App& command);

// estimate_spacing of a cloud read from `file`, its errors ("the points coincide") naming
// the file.
SpacingEstimate estimate_spacing_of(const PointCloud& cloud, const std::string& file);

// --support adaptive|global (points/support.hpp); `choice` is empty when the flag is not
// given: adaptive then, unless --h fixed one width for every sample.
void add_support_option(CLI::App& command, std::string& choice);
Support support_of(const std::string& choice, bool h_given);
// "global support", or "adaptive support, h_i from X to Y", for the summary line.
std::string support_text(Support support, const SupportWidths& widths);

// --surface mls|apss|rimls, --normals file|estimate and --outliers set-aside|keep
// (points/projection.hpp): which surface the samples define, and which points are samples.
struct SurfaceOptions {
  std::string surface = "mls";
  std::string normals = "file";
  std::string outliers = "set-aside";
};
void add_surface_options(CLI::App& command, SurfaceOptions& options);
void apply_surface_options(const SurfaceOptions& options, ProjectionParams& params);
// " (the file's normals)", " (estimated normals)" or "", after "<surface> surface".
const char* normals_text(NormalsUsed used);

// A line on stdout when some of the file's normals were turned as contradicting the points
// (points/turn_flipped_normals.hpp); nothing when none were.
void print_normals_turned(std::size_t turned, std::size_t points);

// What a chosen subcommand does once CLI11 has parsed and validated its options: run, or
// only check the options that need more than one flag's validator (the --iso/--gradient
// choice, the raw-volume flags together), which reads no file and writes none. The fuzz
// target of the option parsing (fuzz/cli.cpp) uses `check`.
enum class Action { run, check };

// The app `pss` is: its subcommands, --version, and one-line usage errors.
void configure_app(CLI::App& app, Action action);

void add_info_command(CLI::App& app, Action action);
void add_project_command(CLI::App& app, Action action);
void add_mesh_command(CLI::App& app, Action action);
void add_render_command(CLI::App& app, Action action);
void add_volume_command(CLI::App& app, Action action);
void add_extract_command(CLI::App& app, Action action);

}  // namespace pss::app
