// The subcommands of `pss`. Each file adds one to the app and runs it when chosen.
#pragma once

#include <CLI/CLI.hpp>
#include <cstdint>
#include <functional>
#include <string>

#include "pss/backend/backend.hpp"
#include "pss/core/error.hpp"
#include "pss/core/stats.hpp"
#include "pss/tiles/memory_plan.hpp"
#include "pss/io/tiled_cloud.hpp"
#include "pss/points/cloud.hpp"
#include "pss/points/projection.hpp"
#include "pss/points/sample_normals.hpp"
#include "pss/points/spacing.hpp"
#include "pss/points/support.hpp"

namespace pss::app {

// The point clouds' formats, for the commands' help.
inline const std::string kCloudFormatsHelp = "point cloud (.ply, .xyz/.txt/.pts, .pwn, .obj, .off, .stl, .pcd, .las)";

// Options every compute subcommand shares.
struct ComputeOptions {
  std::string backend = "auto";
  int threads = 0;
  std::string stats_path;
};
void add_compute_options(CLI::App& command, ComputeOptions& options);  // with --progress
// --threads applied, and the backend --backend names.
Backend start_compute(const ComputeOptions& options);

// "1 thread" or "N threads": the CPU threads that the summary lines name.
std::string threads_text();
// make()'s result, its errors naming `file`: what the data cannot give is the file's fault,
// the flags having been checked already.
template <class Make>
auto naming_input(const std::string& file, Make&& make) {
  try {
    return make();
  } catch (const NotTiled&) {
    throw;  // for the caller to run in core
  } catch (const Error& e) {
    throw file_error(file, e.what());
  }
}

// The cloud of `file`, its reading timed (phase "read").
PointCloud read_cloud(const std::string& file, Stats& stats);
// What every command's --stats records of a run: the command, its input and output, backend
// and threads; of a run on a cloud also the points and their origin (the written positions
// include it).
void record_run(Stats& stats, const char* command, const std::string& input, const std::string& output,
                Backend backend);
void record_cloud_run(Stats& stats, const char* command, const std::string& input, const std::string& output,
                      const PointCloud& cloud, Backend backend);
void record_cloud_run(Stats& stats, const char* command, const std::string& input, const std::string& output,
                      std::uint64_t points, glm::dvec3 origin, Backend backend);
// --progress auto|always|never: sets the process's ProgressMode when given.
void add_progress_option(CLI::App& command);

// --memory SIZE (tiles/memory_plan.hpp): the most memory a command on a cloud may take; a
// cloud that needs more is worked on tile by tile. `what` says what comes out the same.
void add_memory_option(CLI::App& command, std::string& size, const std::string& what);
// The budget --memory gives, or default_memory_budget() where it is not given.
std::uint64_t memory_budget(const std::string& size);
// "N tiles of about M points": the tiles that hold points, and their mean.
std::string tiles_text(const TiledCloud& tiles);

// estimate_spacing of a cloud read from `file`, its errors ("the points coincide") naming
// the file.
SpacingEstimate estimate_spacing_of(const PointCloud& cloud, const std::string& file);
// Throws an Error naming `file` where its `points` are too few for the default h (which --h
// then must give).
void check_enough_for_default_h(std::size_t points, const std::string& file);

// --support adaptive|global (points/support.hpp); `choice` is empty when the flag is not
// given: adaptive then, unless --h fixed one width for every sample.
void add_support_option(CLI::App& command, std::string& choice);
Support support_of(const std::string& choice, bool h_given);
// "global support", or "adaptive support, h_i from X to Y", for the summary line.
std::string support_text(Support support, const SupportWidths& widths);

// --surface mls|apss|rimls, --normals file|estimate and --outliers set-aside|keep
// (points/projection.hpp): which surface the samples define, and which points are samples.
struct SurfaceOptions {
  std::string surface = "rimls";
  std::string normals = "file";
  std::string outliers = "set-aside";
};
void add_surface_options(CLI::App& command, SurfaceOptions& options);
void apply_surface_options(const SurfaceOptions& options, ProjectionParams& params);
// " (the file's normals)", " (estimated normals)" or "", after "<surface> surface".
const char* normals_text(NormalsUsed used);

// The flags of a cloud's PSS that `project` and `mesh` share: --h, --rho, --support,
// --surface, --normals, --outliers and --iterations.
struct CloudSurfaceFlags {
  float h = 0, rho = 0;
  std::string support;  // empty: support_of's default
  SurfaceOptions surface;
  int iterations = 0;  // 0: default_iterations of the surface
};
void add_cloud_surface_flags(CLI::App& command, CloudSurfaceFlags& flags);
// The projection's parameters the flags give, h estimated from the spacing of `cloud` (read
// from `file`; phase "estimate h") when --h is not given.
ProjectionParams projection_params(const CloudSurfaceFlags& flags, const PointCloud& cloud, const std::string& file,
                                   PlaneFitMethod plane, Stats& stats);
// The same, h from `estimate_h` (phase "estimate h") when --h is not given.
ProjectionParams projection_params(const CloudSurfaceFlags& flags, const std::function<float()>& estimate_h,
                                   PlaneFitMethod plane, Stats& stats);

// A line on stdout when some of the file's normals were turned as contradicting the points
// (points/turn_flipped_normals.hpp); nothing when none were.
void print_normals_turned(std::size_t turned, std::size_t points);

// A line on stdout when the file's normals were left out as not following the points: `off`
// of the samples' lay more than 45° off their neighbours' plane (points/sample_normals.hpp:
// FileNormals); nothing when 0.
void print_file_normals_off(std::size_t off, std::size_t points);

// How many of the cloud's normals have no direction (zero or not finite) where --normals file
// (the default) asks for them; 0 otherwise. One is enough for all to be left out and
// estimated (points/sample_normals.hpp: file_normals): the summaries say so with
// print_file_normals_left_out (a mesh's vertex normals are 0 at its unused vertices).
std::size_t file_normals_without_direction(const PointCloud& cloud, const SurfaceOptions& options);
void print_file_normals_left_out(std::size_t without_direction, std::size_t points);

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
