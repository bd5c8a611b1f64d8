#include "pss/backend/backend.hpp"
#include "pss/backend/cuda/runtime.cuh"

namespace pss::cuda {

bool built() { return true; }

int device_count() {
  int count = 0;
  // No driver or no device both mean "none here", not an error.
  if (cudaGetDeviceCount(&count) != cudaSuccess) {
    cudaGetLastError();
    return 0;
  }
  return count;
}

std::string device_name() {
  if (device_count() == 0) return "none";
  cudaDeviceProp prop{};
  PSS_CUDA_CHECK(cudaGetDeviceProperties(&prop, 0));
  return prop.name;
}

}  // namespace pss::cuda
