// The options `pss volume`, `pss extract` and `pss mesh` share: how to read the volume (raw
// flags or a format with a header), which surface (--iso V or --gradient), and the method's
// parameters, with the documented defaults in voxel units.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "raw_volume_options.hpp"
#include "pss/volume/render_volume.hpp"

namespace pss::app {

struct VolumeOptions {
  std::string input;
  RawVolumeOptions raw;  // raw volumes only
  const CLI::Option* iso_option = nullptr;        // counts whether --iso was given
  const CLI::Option* threshold_option = nullptr;  // and --threshold
  std::string method = "predictor-corrector";
  VolumeSettings settings;  // the library's defaults; method set from `method`
};

// The volume's file, its raw flags, and add_volume_surface_flags with --h and --k.
void add_volume_options(CLI::App& command, VolumeOptions& options, bool method_flag);
// --iso, --gradient, --method (with method_flag), --h and --k (with width_flags), --radius,
// --alpha, --smoothing, --error and --threshold.
void add_volume_surface_flags(CLI::App& command, VolumeOptions& options, bool method_flag, bool width_flags);

// The checks of flags together that CLI11's validators cannot make (--iso or --gradient,
// --threshold with --gradient, the raw flags: raw_volume_format); throws a one-line Error.
// Reads nothing.
std::optional<RawVolumeFormat> check_volume_options(const VolumeOptions& options);

// check_volume_options, then reads the volume, computes gradients, weights and bricks;
// every parameter resolved.
PreparedVolume load_volume(const VolumeOptions& options, Stats& stats);

// The resolved feature and method parameters, for --stats.
nlohmann::json describe(const PreparedVolume& volume, const VolumeOptions& options);

}  // namespace pss::app
