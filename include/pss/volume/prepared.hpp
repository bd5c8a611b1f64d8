// What rendering and extraction prepare once per volume and feature (gradients, weights,
// surface cells, bricks), and the scene's arrays as one backend's kernels see them.
#pragma once

#include <cstdint>

#include "pss/backend/mirror.hpp"
#include "pss/core/stats.hpp"
#include "pss/volume/marcher.hpp"
#include "pss/volume/settings.hpp"

namespace pss {

struct PreparedVolume {
  VolumeFields fields;
  SurfaceCells cells;
  BrickGrid bricks;
  FeatureParams feature;
  VolumeParams params;

  VolumeScene scene() const { return {fields.view(), cells.view(), bricks.view(), feature, params}; }
  // What a camera should frame: the cells the surface crosses, or the whole box if none.
  Aabb surface_bounds() const {
    return cells.crossed_bounds.empty() ? fields.volume.view().bounds() : cells.crossed_bounds;
  }
};

// Weights, surface cells and bricks for `feature` (fields must hold the gradients).
PreparedVolume prepare_volume(VolumeFields fields, const FeatureParams& feature, const VolumeParams& params,
                              Stats& stats);

// validate(settings), then the gradients, weights, surface cells and bricks of `volume` with
// every parameter resolved in its voxel size. Throws a one-line Error when the iso-value lies
// outside the volume's values (no surface) or a neighbourhood would overflow the kernels' buffer.
PreparedVolume prepare_volume(Volume volume, const VolumeSettings& settings, Stats& stats);

// A VolumeScene whose arrays are on `backend` (on the CPU, the prepared volume's own).
class SceneMirror {
 public:
  SceneMirror(Backend backend, const PreparedVolume& volume);
  const VolumeScene& scene() const { return scene_; }

 private:
  Mirror<float> values_;
  Mirror<vec3> gradients_;
  Mirror<FeatureVoxel> features_;
  Mirror<std::uint8_t> occupied_;
  Mirror<std::uint8_t> cell_flags_;
  VolumeScene scene_;
};

}  // namespace pss
