#include "volume_options.hpp"

#include <cfloat>

#include "numbers.hpp"
#include "pss/core/error.hpp"
#include "pss/io/volume_file.hpp"

namespace pss::app {

void add_volume_options(CLI::App& command, VolumeOptions& o, bool method_flag) {
  command.add_option("file", o.input, "volume: .nrrd/.nhdr, .mhd/.mha, .nii/.nii.gz, or raw with --dims and --type")
      ->required();
  add_raw_volume_options(command, o.raw);
  add_volume_surface_flags(command, o, method_flag, true);
}

void add_volume_surface_flags(CLI::App& command, VolumeOptions& o, bool method_flag, bool width_flags) {
  auto* iso = command.add_option("--iso", o.settings.iso, "iso-surface f = V (theta1 weights)")
                  ->check(finite_number());
  auto* gradient = command.add_flag("--gradient", o.settings.gradient, "surface of high gradient magnitude (theta2 weights)");
  iso->excludes(gradient);
  gradient->excludes(iso);
  if (method_flag)
    command.add_option("--method", o.method, "predictor (Eq. 3) or predictor-corrector (Eq. 3 then Eq. 4)")
        ->check(CLI::IsMember({"predictor", "predictor-corrector"}))
        ->capture_default_str();
  if (width_flags) {
    command.add_option("--h", o.settings.h, "theta3 width h in voxels (u = (sx*sy*sz)^(1/3)), at least 0.5")
        ->check(finite_range(kMinVolumeH, FLT_MAX))
        ->capture_default_str();
    command.add_option("--k", o.settings.k, "step b = k*h (paper 5.1 takes 0.5 < k < 1)")
        ->check(finite_range(kMinStepK, kMaxStepK))
        ->capture_default_str();
  }
  command
      .add_option("--radius", o.settings.radius,
                  "neighbourhood radius in units of h: the voxels within it are N(.); h*radius at most about 9 voxels "
                  "on a cubic grid (the kernels hold 4096 voxels)")
      ->check(finite_range(kMinRadius, kMaxRadius))
      ->capture_default_str();
  command.add_option("--alpha", o.settings.alpha, "alpha1 of the corrector's Theta = alpha1*theta + (1-alpha1)*theta3")
      ->check(finite_range(0, 1))
      ->capture_default_str();
  command.add_option("--smoothing", o.settings.smoothing,
                     "k of theta1 in voxels: the width of its Gaussian in the distance |V - f|/|grad f| of a voxel "
                     "to the iso-surface")
      ->check(finite_positive())
      ->capture_default_str();
  command.add_option("--error", o.settings.error, "epsilon in voxels: r is a hit when |gamma - r| <= epsilon")
      ->check(finite_positive())
      ->capture_default_str();
  o.threshold_option = command.add_option("--threshold", o.settings.threshold,
                     "gradient surfaces: samples with (|grad f|/max)^2 > T are projected (default 0.5); iso-surfaces "
                     "are looked for next to the cells the data crosses V in, with no threshold")
      ->check(finite_range(0, 1));
  o.iso_option = iso;
}

std::optional<RawVolumeFormat> check_volume_options(const VolumeOptions& o) {
  if (o.iso_option->count() == 0 && !o.settings.gradient) throw Error("choose the surface: --iso V or --gradient");
  if (o.threshold_option->count() > 0 && !o.settings.gradient)
    throw Error("--threshold applies to --gradient surfaces only");
  return raw_volume_format(o.raw, o.input);
}

PreparedVolume load_volume(const VolumeOptions& o, Stats& stats) {
  const std::optional<RawVolumeFormat> raw = check_volume_options(o);
  Volume volume;
  {
    ScopedPhase phase(stats, "read");
    volume = read_volume(o.input, raw);
  }
  VolumeSettings settings = o.settings;
  settings.method = o.method == "predictor" ? VolumeMethod::predictor : VolumeMethod::predictor_corrector;
  try {
    return prepare_volume(std::move(volume), settings, stats);
  } catch (const Error& e) {
    throw file_error(o.input, e.what());  // the flags are checked already: it is the file's
  }
}

nlohmann::json describe(const PreparedVolume& v, const VolumeOptions& o) {
  const VolumeView view = v.fields.volume.view();
  nlohmann::json j;
  j["dims"] = {view.dims.x, view.dims.y, view.dims.z};
  j["spacing"] = {view.spacing.x, view.spacing.y, view.spacing.z};
  j["origin"] = {view.origin.x, view.origin.y, view.origin.z};
  j["max_gradient"] = v.fields.max_gradient;
  j["bricks"] = {{"total", v.bricks.occupied.size()}, {"occupied", v.bricks.occupied_count}};
  j["crossed_cells"] = v.cells.crossed_count;
  if (v.feature.kind == FeatureKind::iso)
    j["feature"] = {{"kind", "iso"}, {"iso", v.feature.iso}, {"smoothing", v.feature.smoothing}};
  else
    j["feature"] = {{"kind", "gradient"}, {"threshold", v.feature.threshold}};
  const VolumeParams& p = v.params;
  j["params"] = {{"method", o.method}, {"h", p.h}, {"k", o.settings.k}, {"b", p.step}, {"radius", p.radius},
                 {"alpha", p.alpha}, {"epsilon", p.epsilon}, {"t_tolerance", p.t_tolerance},
                 {"max_predictor_iterations", p.max_predictor_iterations},
                 {"max_corrector_iterations", p.max_corrector_iterations}, {"max_retries", p.max_retries}};
  return j;
}

}  // namespace pss::app
