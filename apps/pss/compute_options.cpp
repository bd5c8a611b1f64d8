#include "commands.hpp"

#include <algorithm>
#include <cstdio>

#include "numbers.hpp"
#include "pss/backend/backend.hpp"
#include "pss/core/error.hpp"
#include "pss/core/memory.hpp"
#include "pss/core/progress.hpp"
#include "pss/io/point_cloud_file.hpp"
#include "pss/tiles/memory_plan.hpp"

namespace pss::app {

void add_compute_options(CLI::App& command, ComputeOptions& options) {
  command.add_option("--backend", options.backend, "cpu, cuda, or auto (CUDA when built with it and a GPU is present)")
      ->check(CLI::IsMember({"cpu", "cuda", "auto"}))
      ->capture_default_str();
  command.add_option("--threads", options.threads, "CPU threads (default: all cores)")
      ->check(finite_range(1, kMaxCpuThreads));
  command.add_option("--stats", options.stats_path, "write timings per phase and run parameters as JSON")
      ->check([](const std::string& path) { return path.empty() ? std::string("an empty name is no file") : std::string(); });
  add_progress_option(command);
}

Backend start_compute(const ComputeOptions& options) {
  set_cpu_threads(options.threads);
  watch_peak_memory(!options.stats_path.empty());
  return select_backend(options.backend);
}

std::string threads_text() {
  const int threads = cpu_threads();
  return std::to_string(threads) + (threads == 1 ? " thread" : " threads");
}

std::string tiles_text(const TiledCloud& tiles) {
  const std::size_t count = tiles.tiles_with_points().size();
  const std::uint64_t mean = count > 0 ? (tiles.size() + count / 2) / count : 0;
  return std::to_string(count) + " tiles of about " + std::to_string(mean) + " points";
}

PointCloud read_cloud(const std::string& file, Stats& stats) {
  ScopedPhase phase(stats, "read");
  return read_point_cloud(file);
}

void record_run(Stats& stats, const char* command, const std::string& input, const std::string& output,
                Backend backend) {
  auto& v = stats.values();
  v["command"] = command;
  v["input"] = input;
  v["output"] = output;
  v["backend"] = backend_name(backend);
  v["threads"] = cpu_threads();
}

void record_cloud_run(Stats& stats, const char* command, const std::string& input, const std::string& output,
                      const PointCloud& cloud, Backend backend) {
  record_cloud_run(stats, command, input, output, cloud.size(), cloud.origin, backend);
}

void record_cloud_run(Stats& stats, const char* command, const std::string& input, const std::string& output,
                      std::uint64_t points, glm::dvec3 origin, Backend backend) {
  record_run(stats, command, input, output, backend);
  auto& v = stats.values();
  v["points"] = points;
  v["origin"] = {origin.x, origin.y, origin.z};
}

void add_memory_option(CLI::App& command, std::string& size, const std::string& what) {
  command
      .add_option("--memory", size,
                  "the most memory the work on a cloud may take (such as 512M or 8G); a cloud that needs more is "
                  "read into tiles in the temporary folder ($TMPDIR) and worked on one tile at a time, with " +
                      what + " (default: half of this machine's memory)")
      ->check(parsed_by(parse_memory_size, "--memory", "SIZE"));
}

std::uint64_t memory_budget(const std::string& size) {
  return size.empty() ? default_memory_budget() : parse_memory_size(size);
}

void add_progress_option(CLI::App& command) {
  command
      .add_option_function<std::string>(
          "--progress",
          [](const std::string& when) {
            set_progress_mode(when == "always"  ? ProgressMode::always
                              : when == "never" ? ProgressMode::never
                                                : ProgressMode::automatic);
          },
          "progress on stderr: auto (a bar while stderr is a terminal), always (a bar on a terminal, else a "
          "line per phase and per 10 %, for logs) or never")
      ->check(CLI::IsMember({"auto", "always", "never"}))
      ->default_str("auto");
}

SpacingEstimate estimate_spacing_of(const PointCloud& cloud, const std::string& file) {
  return naming_input(file, [&] { return estimate_spacing(cloud.positions); });
}

void add_support_option(CLI::App& command, std::string& choice) {
  command
      .add_option("--support", choice,
                  "each sample's Gaussian width h_i: adaptive (h, or wider where the distance to the 15th nearest "
                  "neighbour is over 4/3 of its median, and at least 3 times the samples' noise where they are "
                  "noisy) or global (h for every sample, as the paper); default adaptive, "
                  "global when --h is given")
      ->check(CLI::IsMember({"adaptive", "global"}));
}

Support support_of(const std::string& choice, bool h_given) {
  if (choice.empty()) return default_support(h_given);
  return choice == "global" ? Support::global : Support::adaptive;
}

std::string support_text(Support support, const SupportWidths& widths) {
  if (support == Support::global) return "global support";
  char text[200];
  std::snprintf(text, sizeof text, "adaptive support, h_i from %g to %g", double(widths.least), double(widths.largest));
  std::string out = text;
  if (widths.merged_count > 0) {  // points/merged_samples.hpp
    std::snprintf(text, sizeof text, ", %lld points merged into samples where a support held over %g",
                  (long long)widths.merged_count, kSupportSamplesMost);
    out += text;
  }
  return out;
}

void add_surface_options(CLI::App& command, SurfaceOptions& options) {
  command
      .add_option("--surface", options.surface,
                  "the surface the points define: mls (the paper's plane and polynomial), apss (algebraic spheres "
                  "fitted to the points and their normals: holds sparse, thin and curved parts) or rimls (robust "
                  "implicit MLS: keeps sharp creases); apss and rimls use the file's normals, or "
                  "estimate them")
      ->check(CLI::IsMember({"mls", "apss", "rimls"}))
      ->capture_default_str();
  command
      .add_option("--normals", options.normals,
                  "the points' normals: file (the file's, when it has them; else estimated) or estimate (from the "
                  "points, the file's ignored)")
      ->check(CLI::IsMember({"file", "estimate"}))
      ->capture_default_str();
  command
      .add_option("--outliers", options.outliers,
                  "set-aside (points farther from their neighbours' plane than the cloud's noise allows, at least h/2, "
                  "or with fewer than 3 neighbours, are not samples of the surface: no floating flakes from strays) or "
                  "keep (every point a sample, as the paper)")
      ->check(CLI::IsMember({"set-aside", "keep"}))
      ->capture_default_str();
}

void apply_surface_options(const SurfaceOptions& options, ProjectionParams& params) {
  params.surface = surface_operator_of(options.surface);
  params.normals = options.normals == "estimate" ? NormalSource::estimate : NormalSource::file;
  params.outliers = options.outliers == "keep" ? OutlierPolicy::keep : OutlierPolicy::set_aside;
}

const char* normals_text(NormalsUsed used) {
  return used == NormalsUsed::file ? " (the file's normals)" : used == NormalsUsed::estimated ? " (estimated normals)" : "";
}

void print_normals_turned(std::size_t turned, std::size_t points) {
  if (turned > 0)
    std::printf("turned %zu of the file's normals (of %zu points): a part of the cloud faced inward, or was flipped "
                "against the rest\n", turned, points);
}

void print_file_normals_off(std::size_t off, std::size_t points) {
  if (off > 0)
    std::printf("left out the file's normals: those of %zu samples (of %zu points) lie more than 45 degrees off their "
                "neighbours' plane: they do not follow the points, so all were estimated from the points\n", off,
                points);
}

std::size_t file_normals_without_direction(const PointCloud& cloud, const SurfaceOptions& options) {
  if (options.normals != "file") return 0;
  return std::size_t(std::count_if(cloud.normals.begin(), cloud.normals.end(), [](vec3 n) { return !has_direction(n); }));
}

void print_file_normals_left_out(std::size_t without_direction, std::size_t points) {
  if (without_direction > 0)
    std::printf("left out the file's normals: %zu of %zu have no direction (zero, not finite, or in an OBJ a vertex "
                "no face gives a normal), so all were estimated from the points\n",
                without_direction, points);
}

void add_cloud_surface_flags(CLI::App& command, CloudSurfaceFlags& flags) {
  command.add_option("--h", flags.h, "Gaussian width h (default: estimated from the spacing and the noise, see pss info)")
      ->check(finite_positive());
  command.add_option("--rho", flags.rho, "range-query radius (default 2h; with adaptive support, at h)")
      ->check(finite_positive());
  add_support_option(command, flags.support);
  add_surface_options(command, flags.surface);
  command
      .add_option("--iterations", flags.iterations,
                  "most MLS alternations of t and n, default 4 (apss, rimls: fits moved to the point, default 8)")
      ->check(finite_range(1, 100));
}

void check_enough_for_default_h(std::size_t points, const std::string& file) {
  // The default h is the points' median distance to their 15th nearest neighbour: a cloud of
  // 15 points or fewer has none, and the estimate spanned the whole cloud (a new user's trial:
  // 4 points were told to give a smaller --h, which they had not given).
  constexpr std::size_t kNeighbours = 15;
  if (points <= kNeighbours)
    throw file_error(file, "has " + std::to_string(points) + (points == 1 ? " point" : " points") +
                               ": too few for the default h (their distance to the 15th nearest neighbour); "
                               "give --h");
}

ProjectionParams projection_params(const CloudSurfaceFlags& flags, const PointCloud& cloud, const std::string& file,
                                   PlaneFitMethod plane, Stats& stats) {
  if (flags.h == 0) check_enough_for_default_h(cloud.size(), file);
  return projection_params(flags, [&] { return float(estimate_spacing_of(cloud, file).suggested_h); }, plane, stats);
}

ProjectionParams projection_params(const CloudSurfaceFlags& flags, const std::function<float()>& estimate_h,
                                   PlaneFitMethod plane, Stats& stats) {
  float h = flags.h;
  if (h == 0) {
    ScopedPhase phase(stats, "estimate h");
    h = estimate_h();
  }
  ProjectionParams params = ProjectionParams::from_h(h, plane);
  if (flags.rho != 0) params.rho = flags.rho;
  params.support = support_of(flags.support, flags.h != 0);
  apply_surface_options(flags.surface, params);
  params.max_mls_iterations = flags.iterations > 0 ? flags.iterations : default_iterations(params.surface);
  return params;
}

}  // namespace pss::app
