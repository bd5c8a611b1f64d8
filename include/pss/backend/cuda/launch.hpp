// The GPU half of pss::parallel_for (backend/parallel_for.hpp) as the host compiler sees it:
// a declaration. Its definition (launch.cuh) is compiled by nvcc only, in the .cu files that
// instantiate it once per kernel type (PSS_CUDA_KERNEL), so that every other file, and the
// CPU side of every kernel, is compiled by the host compiler.
#pragma once

#include <cstdint>

namespace pss {
class Progress;
}

namespace pss::cuda {

// kernel(i) for i in [0, n) on the GPU; returns the phase's device time.
template <class Kernel>
double launch(const char* phase, std::int64_t n, const Kernel& kernel, Progress* progress);

}  // namespace pss::cuda
