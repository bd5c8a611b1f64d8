#include "device_volume.cuh"
#include "pss/volume/extract.hpp"

namespace pss::cuda {

void extract_candidates(const VolumeScene& host_scene, const ExtractLattice& lattice, std::span<ExtractedPoint> out,
                        Progress* progress) {
  const DeviceVolume volume(host_scene);
  DeviceBuffer<ExtractedPoint> d_out(out.size());
  const VolumeScene s = volume.scene();
  const ExtractLattice l = lattice;
  ExtractedPoint* o = d_out.data();
  parallel_for("extraction", l.size(), [=] __device__(std::int64_t i) { o[i] = extract_candidate(s, l.at(i)); },
               progress);
  d_out.download(out);
}

}  // namespace pss::cuda
