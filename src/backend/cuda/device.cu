// The CUDA device queries and the device memory behind Mirror (backend/mirror.hpp).
#include "pss/backend/backend.hpp"
#include "pss/backend/cuda/launch.cuh"

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
  int device = 0;
  PSS_CUDA_CHECK(cudaGetDevice(&device));
  cudaDeviceProp prop{};
  PSS_CUDA_CHECK(cudaGetDeviceProperties(&prop, device));
  return prop.name;
}

void use_device(int index) {
  const int count = device_count();
  if (count > 0) PSS_CUDA_CHECK(cudaSetDevice(index % count));
}

void* allocate(std::size_t bytes) {
  void* p = nullptr;
  PSS_CUDA_CHECK(cudaMalloc(&p, bytes));
  // Zeroed, so that the padding of the structs kernels write is defined when it is copied
  // back (compute-sanitizer's initcheck reports it otherwise).
  const cudaError_t status = cudaMemset(p, 0, bytes);
  if (status != cudaSuccess) cudaFree(p);
  check(status, "cudaMemset");
  return p;
}

void release(void* device) noexcept { cudaFree(device); }

void upload(void* device, const void* host, std::size_t bytes) {
  PSS_CUDA_CHECK(cudaMemcpy(device, host, bytes, cudaMemcpyHostToDevice));
}

void download(void* host, const void* device, std::size_t bytes) {
  PSS_CUDA_CHECK(cudaMemcpy(host, device, bytes, cudaMemcpyDeviceToHost));
}

}  // namespace pss::cuda
