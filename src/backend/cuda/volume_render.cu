#include "device_volume.cuh"
#include "render_frame.cuh"
#include "pss/volume/render_volume.hpp"

namespace pss::cuda {

RenderedFrame render_volume(const VolumeScene& host_scene, const Camera& camera, const TraceSettings& settings,
                            Stats& stats) {
  const DeviceVolume volume(host_scene);
  return render_frame_device(VolumeFinder{volume.scene()}, camera, settings, stats);
}

}  // namespace pss::cuda
