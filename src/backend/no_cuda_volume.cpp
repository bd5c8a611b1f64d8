// The CUDA entry points of the volume method in a build without nvcc (see no_cuda.cpp).
#include "pss/core/error.hpp"
#include "pss/volume/extract.hpp"

namespace pss::cuda {

RenderedFrame render_volume(const VolumeScene&, const Camera&, const TraceSettings&, Stats&) {
  throw Error("this pss was built without CUDA");
}

void extract_candidates(const VolumeScene&, const ExtractLattice&, std::span<ExtractedPoint>, Progress*) {
  throw Error("this pss was built without CUDA");
}

}  // namespace pss::cuda
