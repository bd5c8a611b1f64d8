// What a user chooses for the PSS of a volume (`pss volume` and `extract`, a viewer, the
// Python module), in voxel units with the documented defaults (VolumeParams::from_voxels,
// docs/paper-notes.md); prepare_volume (prepared.hpp) resolves them against the volume.
#pragma once

#include "pss/volume/fields.hpp"
#include "pss/volume/projection.hpp"

namespace pss {

// The smallest h, in voxels. Rays march in steps b = k·h, so the work grows as 1/h while the
// surface gets no finer below the voxels (a neighbourhood of 1.5h holds a few voxels at
// most): h = 1e-10 had not finished an 8×8 image of the 32³ bucky after 20 s; at 0.5 with
// the smallest k, 0.05, a 512×512 image of it takes 6 s on 2 cores.
inline constexpr float kMinVolumeH = 0.5f;
// The ranges of k and of the radius (units of h) that validate() and the CLI's flags take
// (doubles: the CLI compares the decimal it parsed, validate() the float it holds).
inline constexpr double kMinStepK = 0.05, kMaxStepK = 1.0;
inline constexpr double kMinRadius = 0.5, kMaxRadius = 4.0;

struct VolumeSettings {
  bool gradient = false;  // the high-gradient surface (θ2), or else
  float iso = 0;          // the iso-surface f = iso (θ1)
  VolumeMethod method = VolumeMethod::predictor_corrector;
  float h = 2;            // θ3's width, voxels (at least kMinVolumeH)
  float k = 0.75f;        // marching step b = k·h, in [kMinStepK, kMaxStepK]
  float radius = 1.5f;    // neighbourhood radius in units of h, in [kMinRadius, kMaxRadius]
  float alpha = 0.9f;     // α1 of the corrector, in [0, 1]
  float error = 0.1f;     // ε, voxels
  float smoothing = kIsoSmoothingVoxels;  // θ1's k, voxels
  float threshold = 0.5f;  // gradient surfaces: (|∇f|/max)² above it is projected (the paper's 0.5)

  bool operator==(const VolumeSettings&) const = default;
};

// Throws a one-line Error naming the setting that is not a finite number in its range.
void validate(const VolumeSettings& settings);

}  // namespace pss
