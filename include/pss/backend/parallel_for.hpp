// The one launcher of both backends: parallel_for(backend, "phase", n, kernel, stats) runs
// kernel(i) for i in [0, n) on every CPU core (OpenMP) or on the GPU, and adds the phase's
// time to stats (on the GPU, device time from CUDA events). A kernel is a struct whose
// members are what it reads (views and Mirror pointers of that backend) with
//   PSS_HOST_DEVICE void operator()(std::int64_t i) const;
// so the code around a kernel is written once for both. Files that launch kernels are C++,
// compiled by the host compiler in every build, which makes the CPU's AVX2 copy of each
// kernel (cpu/parallel_for.hpp); the GPU's code of each kernel type is made in one .cu file
// (PSS_CUDA_KERNEL in cuda/launch.cuh). The phase is shown on stderr unless a Progress is
// given (it shows it) or `announce` is false (the caller shows a step of many launches whole).
#pragma once

#include <cstdint>

#include "pss/backend/backend.hpp"
#include "pss/backend/cpu/parallel_for.hpp"
#include "pss/core/platform.hpp"
#include "pss/core/progress.hpp"
#include "pss/core/stats.hpp"

#if PSS_HAVE_CUDA
#include "pss/backend/cuda/launch.hpp"
#endif

namespace pss {

template <class Kernel>
void parallel_for(Backend backend, const char* phase, std::int64_t n, const Kernel& kernel, Stats& stats,
                  Progress* progress = nullptr, bool announce = true) {
  if (backend == Backend::cuda) {
#if PSS_HAVE_CUDA
    if (!progress && announce) Progress::phase_begun(phase);
    const int peak_watch = begin_peak_watch();
    const double seconds = n > 0 ? cuda::launch(phase, n, kernel, progress) : 0.0;
    stats.add_time(phase, seconds);
    stats.add_peak(phase, end_peak_watch(peak_watch));
    if (!progress && announce) Progress::phase_ended(phase, seconds);
#else
    cuda_not_built(phase);
#endif
    return;
  }
  ScopedPhase timed(stats, phase, progress == nullptr && announce);  // a Progress shows it already
  cpu::parallel_for(n, kernel, progress);
}

}  // namespace pss
