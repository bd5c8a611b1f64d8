// The definition of cuda::launch (launch.hpp), for the .cu files that instantiate it: every
// runtime call checked, the block size from the occupancy API, and each named phase timed
// with CUDA events.
#pragma once

#include <cuda_runtime.h>

#include <cstdint>
#include <string>

#include "pss/backend/cuda/launch.hpp"
#include "pss/core/error.hpp"
#include "pss/core/progress.hpp"

namespace pss::cuda {

inline void check(cudaError_t status, const char* what) {
  if (status != cudaSuccess) throw Error(std::string("CUDA error in ") + what + ": " + cudaGetErrorString(status));
}
#define PSS_CUDA_CHECK(call) ::pss::cuda::check((call), #call)

// The block size that keeps the most threads of this kernel resident (its registers and
// stack decide), found once per kernel, at most 128: our items diverge (rays that miss
// next to rays that project 30 candidates), and a block holds its place on the SM until its
// slowest warp ends. Uncapped, the occupancy API's choice made 1920×1080 frames 13.0 → 16.9 ms
// on an H100 (docs/benchmarks.md).
inline constexpr int kMaxBlock = 128;

// The blocks of kMaxBlock threads that a kernel asks the compiler to fit on one SM at once,
// through its registers: 1 leaves the compiler free (the bound then only says that no block
// has more than kMaxBlock threads). Specialised where a kernel is instantiated (its .cu file).
template <class F>
inline constexpr int kMinBlocksPerSm = 1;

template <class F>
__global__ void __launch_bounds__(kMaxBlock, kMinBlocksPerSm<F>) for_each_index(std::int64_t begin, std::int64_t end, F f) {
  const std::int64_t i = begin + std::int64_t(blockIdx.x) * blockDim.x + threadIdx.x;
  if (i < end) f(i);
}

template <class F>
int block_size(const char* phase) {
  static const int block = [&] {
    int min_grid = 0, size = 0;
    check(cudaOccupancyMaxPotentialBlockSize(&min_grid, &size, for_each_index<F>, 0, kMaxBlock), phase);
    return size;
  }();
  return block;
}

class PhaseTimer {
 public:
  explicit PhaseTimer(const char* phase) : phase_(phase) {
    check(cudaEventCreate(&start_), phase);
    check(cudaEventCreate(&stop_), phase);
    check(cudaEventRecord(start_), phase);
  }
  ~PhaseTimer() {
    cudaEventDestroy(start_);
    cudaEventDestroy(stop_);
  }
  PhaseTimer(const PhaseTimer&) = delete;
  PhaseTimer& operator=(const PhaseTimer&) = delete;
  // Waits for the phase's kernels; their errors surface here, named by the phase.
  double seconds() {
    check(cudaEventRecord(stop_), phase_);
    check(cudaEventSynchronize(stop_), phase_);
    check(cudaGetLastError(), phase_);
    float ms = 0;
    check(cudaEventElapsedTime(&ms, start_, stop_), phase_);
    return 1e-3 * ms;
  }

 private:
  const char* phase_;
  cudaEvent_t start_{}, stop_{};
};

// A progress bar that is shown splits the work into batches, waiting for each; otherwise it
// is one launch.
template <class F>
double launch(const char* phase, std::int64_t n, const F& f, Progress* progress) {
  const int block = block_size<F>(phase);
  PhaseTimer timer(phase);
  const std::int64_t batch = progress && progress->shown() ? std::int64_t(1) << 16 : n;
  for (std::int64_t begin = 0; begin < n; begin += batch) {
    const std::int64_t end = begin + batch < n ? begin + batch : n;
    const unsigned blocks = unsigned((end - begin + block - 1) / block);
    for_each_index<<<blocks, block>>>(begin, end, f);
    check(cudaGetLastError(), phase);
    if (batch < n) {
      check(cudaDeviceSynchronize(), phase);
      progress->advance(end - begin);
    }
  }
  return timer.seconds();
}

}  // namespace pss::cuda

// The one instantiation of cuda::launch for a kernel type, in a .cu file.
#define PSS_CUDA_KERNEL(...) \
  template double pss::cuda::launch<__VA_ARGS__>(const char*, std::int64_t, const __VA_ARGS__&, pss::Progress*);
