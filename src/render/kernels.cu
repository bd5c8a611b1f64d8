// The GPU code of the render kernels that do not depend on a surface finder
// (backend/cuda/launch.hpp); those that do are made with their finder's (points/, volume/).
#include "pss/backend/cuda/launch.cuh"
#include "pss/render/frame_kernels.hpp"

PSS_CUDA_KERNEL(pss::HitCountsKernel)
