// The CUDA entry points of the renderer in a build without nvcc (see no_cuda.cpp).
#include "pss/core/error.hpp"
#include "pss/points/render_cloud.hpp"

namespace pss::cuda {

void fit_local_polynomials(const GridView&, std::span<const vec3>, std::span<const vec3>, float, float,
                           std::span<LocalFit>, Progress*) {
  throw Error("this pss was built without CUDA");
}

RenderedFrame render_points(const PointSurfaceView&, const Camera&, const TraceSettings&, Stats&) {
  throw Error("this pss was built without CUDA");
}

}  // namespace pss::cuda
