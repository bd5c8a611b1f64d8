// The CUDA entry points of a build without nvcc: they say so. select_backend() never picks
// CUDA in such a build, so the kernels' entry points are unreachable but still link.
#include "pss/backend/backend.hpp"
#include "pss/core/error.hpp"
#include "pss/points/project_cloud.hpp"

namespace pss::cuda {

namespace {
[[noreturn]] void unavailable() { throw Error("this pss was built without CUDA"); }
}  // namespace

bool built() { return false; }
int device_count() { return 0; }
std::string device_name() { return "none"; }

void project_points(const GridView&, std::span<const vec3>, std::span<const vec3>, const ProjectionParams&,
                    std::span<ProjectedPoint>, Progress*) {
  unavailable();
}

}  // namespace pss::cuda
