// A volume scene in device memory: values, gradients, feature weights, cells and bricks uploaded
// once, and the same VolumeScene view pointing at them.
#pragma once

#include "pss/backend/cuda/runtime.cuh"
#include "pss/volume/marcher.hpp"

namespace pss::cuda {

class DeviceVolume {
 public:
  explicit DeviceVolume(const VolumeScene& host) : scene_(host) {
    const VolumeView& v = host.fields.volume;
    const std::size_t voxels = std::size_t(v.dims.x) * std::size_t(v.dims.y) * std::size_t(v.dims.z);
    const std::size_t bricks = std::size_t(host.bricks.count.x) * host.bricks.count.y * host.bricks.count.z;
    values_ = DeviceBuffer<float>(std::span<const float>(v.values, voxels));
    gradients_ = DeviceBuffer<vec3>(std::span<const vec3>(host.fields.gradients, voxels));
    weights_ = DeviceBuffer<float>(std::span<const float>(host.fields.weights, voxels));
    const std::size_t cells = std::size_t(host.cells.count.x) * host.cells.count.y * host.cells.count.z;
    occupied_ = DeviceBuffer<std::uint8_t>(std::span<const std::uint8_t>(host.bricks.occupied, bricks));
    cell_flags_ = DeviceBuffer<std::uint8_t>(std::span<const std::uint8_t>(host.cells.flags, cells));
    scene_.fields.volume.values = values_.data();
    scene_.fields.gradients = gradients_.data();
    scene_.fields.weights = weights_.data();
    scene_.bricks.occupied = occupied_.data();
    scene_.cells.flags = cell_flags_.data();
  }
  const VolumeScene& scene() const { return scene_; }

 private:
  VolumeScene scene_;
  DeviceBuffer<float> values_;
  DeviceBuffer<vec3> gradients_;
  DeviceBuffer<float> weights_;
  DeviceBuffer<std::uint8_t> occupied_;
  DeviceBuffer<std::uint8_t> cell_flags_;
};

}  // namespace pss::cuda
