#include "volume_options.hpp"

#include <cfloat>

#include "numbers.hpp"
#include "pss/core/error.hpp"
#include "pss/io/volume_file.hpp"
#include "pss/volume/histogram.hpp"

namespace pss::app {

namespace {

// The smallest --h, in voxels. Rays march in steps b = k*h, so the work grows as 1/h while
// the surface gets no finer below the voxels (a neighbourhood of 1.5h holds a few voxels at
// most): --h 1e-10 had not finished an 8x8 image of the 32^3 bucky after 20 s; at 0.5 with
// the smallest --k, 0.05, a 512x512 image of it takes 6 s on 2 cores.
constexpr double kMinVolumeH = 0.5;

// An iso-value the data never reaches has no surface: say so, with the range.
void check_iso_value(const Volume& volume, const std::string& file, float iso) {
  const ValueStats range = value_stats(volume.values);
  if (!(iso >= range.min && iso <= range.max))
    throw Error("--iso " + format_number(iso) + " lies outside the values of " + file + ": [" +
                format_number(range.min) + ", " + format_number(range.max) + "]");
}

}  // namespace

void add_volume_options(CLI::App& command, VolumeOptions& o, bool method_flag) {
  command.add_option("file", o.input, "volume: .nrrd/.nhdr, .mhd/.mha, .nii/.nii.gz, or raw with --dims and --type")
      ->required();
  add_raw_volume_options(command, o.raw);
  auto* iso = command.add_option("--iso", o.iso, "iso-surface f = V (theta1 weights)")
                  ->check(finite_number());
  auto* gradient = command.add_flag("--gradient", o.gradient, "surface of high gradient magnitude (theta2 weights)");
  iso->excludes(gradient);
  gradient->excludes(iso);
  if (method_flag)
    command.add_option("--method", o.method, "predictor (Eq. 3) or predictor-corrector (Eq. 3 then Eq. 4)")
        ->check(CLI::IsMember({"predictor", "predictor-corrector"}))
        ->capture_default_str();
  command.add_option("--h", o.h, "theta3 width h in voxels (u = (sx*sy*sz)^(1/3)), at least 0.5")
      ->check(finite_range(kMinVolumeH, FLT_MAX))
      ->capture_default_str();
  command.add_option("--k", o.k, "step b = k*h, 0.5 < k < 1 (paper 5.1)")
      ->check(finite_range(0.05, 1))
      ->capture_default_str();
  command.add_option("--radius", o.radius, "neighbourhood radius in units of h: the voxels within it are N(.)")
      ->check(finite_range(0.5, 4))
      ->capture_default_str();
  command.add_option("--alpha", o.alpha, "alpha1 of the corrector's Theta = alpha1*theta + (1-alpha1)*theta3")
      ->check(finite_range(0, 1))
      ->capture_default_str();
  command.add_option("--smoothing", o.smoothing,
                     "k of theta1 in voxels: the width of its Gaussian in the distance |V - f|/|grad f| of a voxel "
                     "to the iso-surface")
      ->check(finite_positive())
      ->capture_default_str();
  command.add_option("--error", o.error, "epsilon in voxels: r is a hit when |gamma - r| <= epsilon")
      ->check(finite_positive())
      ->capture_default_str();
  command.add_option("--threshold", o.threshold,
                     "gradient surfaces: samples with (|grad f|/max)^2 > T are projected (default 0.5); iso-surfaces "
                     "are looked for next to the cells the data crosses V in, with no threshold")
      ->check(finite_range(0, 1));
  o.iso_option = iso;
}

std::optional<RawVolumeFormat> check_volume_options(const VolumeOptions& o) {
  if (o.iso_option->count() == 0 && !o.gradient) throw Error("choose the surface: --iso V or --gradient");
  if (o.threshold > 0 && !o.gradient) throw Error("--threshold applies to --gradient surfaces only");
  return raw_volume_format(o.raw);
}

PreparedVolume load_volume(const VolumeOptions& o, Stats& stats) {
  const std::optional<RawVolumeFormat> raw = check_volume_options(o);
  Volume volume;
  {
    ScopedPhase phase(stats, "read");
    volume = read_volume(o.input, raw);
  }
  if (!o.gradient) check_iso_value(volume, o.input, o.iso);
  VolumeFields fields;
  {
    ScopedPhase phase(stats, "gradients");
    fields = compute_fields(std::move(volume));
  }
  const float voxel = fields.volume.view().voxel_size();
  VolumeParams params = VolumeParams::from_voxels(
      voxel, o.method == "predictor" ? VolumeMethod::predictor : VolumeMethod::predictor_corrector, o.h, o.k, o.alpha,
      o.error, o.radius * o.h);
  const FeatureParams feature = o.gradient ? gradient_feature(o.threshold) : iso_feature(o.iso, o.smoothing * voxel);
  return prepare_volume(std::move(fields), feature, params, stats);
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
  j["params"] = {{"method", o.method}, {"h", p.h}, {"k", o.k}, {"b", p.step}, {"radius", p.radius},
                 {"alpha", p.alpha}, {"epsilon", p.epsilon}, {"t_tolerance", p.t_tolerance},
                 {"max_predictor_iterations", p.max_predictor_iterations},
                 {"max_corrector_iterations", p.max_corrector_iterations}, {"max_retries", p.max_retries}};
  return j;
}

}  // namespace pss::app
