#include "pss/volume/prepared.hpp"

#include <cmath>
#include <cstdio>
#include <string>

#include "pss/core/error.hpp"
#include "pss/core/text.hpp"
#include "pss/volume/histogram.hpp"

namespace pss {

PreparedVolume prepare_volume(VolumeFields fields, const FeatureParams& feature, const VolumeParams& params,
                              Stats& stats) {
  // The kernels hold at most kMaxNeighbours voxels per neighbourhood: refuse a radius that
  // could need more here, rather than let a gather stop early.
  const float bound = neighbourhood_bound(params.radius, fields.volume.view());
  if (bound > float(kMaxNeighbours)) {
    char message[200];
    std::snprintf(message, sizeof message,
                  "a neighbourhood radius of %g holds up to %.0f voxels on this grid, more than the %d the kernels "
                  "hold; use a smaller h or radius", double(params.radius), double(bound), int(kMaxNeighbours));
    throw Error(message);
  }
  PreparedVolume out;
  out.fields = std::move(fields);
  out.feature = feature;
  out.params = params;
  {
    ScopedPhase phase(stats, "feature weights");
    set_feature(out.fields, feature);
  }
  {
    ScopedPhase phase(stats, "bricks");
    // Projecting the samples within b/2 of a crossed cell finds every crossing of a ray, and
    // the ball of trust b takes the projection there. Reaching farther (b, b + 1 voxel) found
    // no hit more on any shipped scan and cost up to 1.6× the projections (engine, iso 90).
    out.cells = find_surface_cells(out.fields, feature, params.sample_reach());
    out.bricks = build_bricks(out.cells);
  }
  return out;
}

void validate(const VolumeSettings& s) {
  const auto check = [](float value, float lo, float hi, const char* name) {
    if (!(std::isfinite(value) && value >= lo && value <= hi))
      throw Error(std::string(name) + " must be a number in [" + format_number(lo) + ", " + format_number(hi) +
                  "] (got " + format_number(value) + ")");
  };
  if (!s.gradient && !std::isfinite(s.iso)) throw Error("the iso-value must be a finite number");
  check(s.h, kMinVolumeH, 1e30f, "h (voxels)");
  check(s.k, float(kMinStepK), float(kMaxStepK), "k");
  check(s.radius, float(kMinRadius), float(kMaxRadius), "radius (units of h)");
  check(s.alpha, 0, 1, "alpha");
  check(s.error, 1e-30f, 1e30f, "error (voxels)");
  check(s.smoothing, 1e-30f, 1e30f, "smoothing (voxels)");
  check(s.threshold, 0, 1, "threshold");
}

PreparedVolume prepare_volume(Volume volume, const VolumeSettings& s, Stats& stats) {
  validate(s);
  // The readers refuse it; a Volume made in code may not have been checked (a negative
  // spacing made every lattice and neighbourhood bound meaningless, and crashed).
  const vec3 sp = volume.spacing;
  if (!(sp.x > 0 && sp.y > 0 && sp.z > 0 && std::isfinite(sp.x) && std::isfinite(sp.y) && std::isfinite(sp.z)))
    throw Error("the voxel spacing " + format_number(sp.x) + "," + format_number(sp.y) + "," + format_number(sp.z) +
                " is not three positive numbers");
  if (!s.gradient) {
    // An iso-value the data never reaches has no surface: say so, with the range.
    const ValueStats range = value_stats(volume.values);
    if (!(s.iso >= range.min && s.iso <= range.max))
      throw Error("the iso-value " + format_number(s.iso) + " lies outside the volume's values [" +
                  format_number(range.min) + ", " + format_number(range.max) + "]");
  }
  VolumeFields fields;
  {
    ScopedPhase phase(stats, "gradients");
    fields = compute_fields(std::move(volume));
  }
  const float voxel = fields.volume.view().voxel_size();
  const VolumeParams params = VolumeParams::from_voxels(voxel, s.method, s.h, s.k, s.alpha, s.error, s.radius * s.h);
  const FeatureParams feature = s.gradient ? gradient_feature(s.threshold) : iso_feature(s.iso, s.smoothing * voxel);
  return prepare_volume(std::move(fields), feature, params, stats);
}

SceneMirror::SceneMirror(Backend backend, const PreparedVolume& volume)
    : values_(backend, volume.fields.volume.values),
      gradients_(backend, volume.fields.gradients),
      features_(backend, volume.fields.features),
      occupied_(backend, volume.bricks.occupied),
      cell_flags_(backend, volume.cells.flags),
      scene_(volume.scene()) {
  scene_.fields.volume.values = values_.data();
  scene_.fields.gradients = gradients_.data();
  scene_.fields.features = features_.data();
  scene_.bricks.occupied = occupied_.data();
  scene_.cells.flags = cell_flags_.data();
}

}  // namespace pss
