// The one launcher of both backends: parallel_for(backend, "phase", n, kernel, stats) runs
// kernel(i) for i in [0, n) on every CPU core (OpenMP) or on the GPU, and adds the phase's
// time to stats (on the GPU, device time from CUDA events). The kernel is a PSS_KERNEL
// lambda, capturing by value what it reads (views and Mirror pointers of that backend), so
// the code around a kernel is written once for both. In a CUDA build a file that launches
// kernels is compiled as CUDA (PSS_KERNEL_SOURCES in src/CMakeLists.txt).
#pragma once

#include <cstdint>

#include "pss/backend/backend.hpp"
#include "pss/backend/cpu/parallel_for.hpp"
#include "pss/core/platform.hpp"
#include "pss/core/progress.hpp"
#include "pss/core/stats.hpp"

#if PSS_HAVE_CUDA
#if !defined(__CUDACC__)
#error "this file launches kernels: compile it as CUDA (add it to PSS_KERNEL_SOURCES in src/CMakeLists.txt)"
#endif
#include "pss/backend/cuda/launch.cuh"
#endif

// A kernel: PSS_KERNEL(std::int64_t i) { ... }
#define PSS_KERNEL [=] PSS_HOST_DEVICE

namespace pss {

template <class Kernel>
void parallel_for(Backend backend, const char* phase, std::int64_t n, const Kernel& kernel, Stats& stats,
                  Progress* progress = nullptr) {
  if (backend == Backend::cuda) {
#if PSS_HAVE_CUDA
    if (!progress) Progress::phase_begun(phase);
    const double seconds = n > 0 ? cuda::launch(phase, n, kernel, progress) : 0.0;
    stats.add_time(phase, seconds);
    if (!progress) Progress::phase_ended(phase, seconds);
#else
    cuda_not_built(phase);
#endif
    return;
  }
  ScopedPhase timed(stats, phase, progress == nullptr);  // a Progress shows it already
  cpu::parallel_for(n, kernel, progress);
}

}  // namespace pss
