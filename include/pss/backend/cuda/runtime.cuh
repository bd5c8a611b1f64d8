// The CUDA backend's plumbing, for .cu files only: every runtime call checked, device memory
// owned by RAII buffers, and one launcher that runs a host+device functor over [0, n).
#pragma once

#include <cuda_runtime.h>

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "pss/core/error.hpp"
#include "pss/core/progress.hpp"

namespace pss::cuda {

inline void check(cudaError_t status, const char* what) {
  if (status != cudaSuccess) throw Error(std::string("CUDA error in ") + what + ": " + cudaGetErrorString(status));
}
#define PSS_CUDA_CHECK(call) ::pss::cuda::check((call), #call)

template <class T>
class DeviceBuffer {
 public:
  DeviceBuffer() = default;
  // Zeroed, so that the padding of the structs kernels write is defined when it is copied back
  // (compute-sanitizer's initcheck reports it otherwise).
  explicit DeviceBuffer(std::size_t n) : size_(n) {
    if (n) {
      PSS_CUDA_CHECK(cudaMalloc(&data_, n * sizeof(T)));
      PSS_CUDA_CHECK(cudaMemset(data_, 0, n * sizeof(T)));
    }
  }
  explicit DeviceBuffer(std::span<const T> host) : DeviceBuffer(host.size()) { upload(host); }
  ~DeviceBuffer() {
    if (data_) cudaFree(data_);
  }
  DeviceBuffer(DeviceBuffer&& other) noexcept : data_(other.data_), size_(other.size_) {
    other.data_ = nullptr;
    other.size_ = 0;
  }
  DeviceBuffer& operator=(DeviceBuffer&& other) noexcept {
    std::swap(data_, other.data_);
    std::swap(size_, other.size_);
    return *this;
  }
  DeviceBuffer(const DeviceBuffer&) = delete;
  DeviceBuffer& operator=(const DeviceBuffer&) = delete;

  void upload(std::span<const T> host) {
    if (host.size() != size_) throw Error("DeviceBuffer::upload: size mismatch");
    if (size_) PSS_CUDA_CHECK(cudaMemcpy(data_, host.data(), size_ * sizeof(T), cudaMemcpyHostToDevice));
  }
  void download(std::span<T> host) const {
    if (host.size() != size_) throw Error("DeviceBuffer::download: size mismatch");
    if (size_) PSS_CUDA_CHECK(cudaMemcpy(host.data(), data_, size_ * sizeof(T), cudaMemcpyDeviceToHost));
  }
  std::vector<T> to_host() const {
    std::vector<T> v(size_);
    download(v);
    return v;
  }
  T* data() { return data_; }
  const T* data() const { return data_; }
  std::size_t size() const { return size_; }

 private:
  T* data_ = nullptr;
  std::size_t size_ = 0;
};

template <class F>
__global__ void for_each_index(std::int64_t begin, std::int64_t end, F f) {
  const std::int64_t i = begin + std::int64_t(blockIdx.x) * blockDim.x + threadIdx.x;
  if (i < end) f(i);
}

// f(i) for i in [0, n) on the device, in batches so that progress can be shown; checks the
// launch and waits for the kernel, so errors surface here with the phase's name.
template <class F>
void parallel_for(const char* name, std::int64_t n, F f, Progress* progress = nullptr) {
  constexpr int block = 128;
  const std::int64_t batch = progress ? std::int64_t(1) << 16 : n;
  for (std::int64_t begin = 0; begin < n; begin += batch) {
    const std::int64_t end = begin + batch < n ? begin + batch : n;
    const unsigned blocks = unsigned((end - begin + block - 1) / block);
    for_each_index<<<blocks, block>>>(begin, end, f);
    check(cudaGetLastError(), name);
    check(cudaDeviceSynchronize(), name);
    if (progress) progress->advance(end - begin);
  }
}

}  // namespace pss::cuda
