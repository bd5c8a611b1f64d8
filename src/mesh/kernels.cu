// The GPU code of the mesh's kernels (backend/cuda/launch.hpp); their CPU code comes from the
// same header, compiled where they are launched (mesh_cloud.cpp).
#include "pss/backend/cuda/launch.cuh"
#include "pss/mesh/cloud_implicit.hpp"

PSS_CUDA_KERNEL(pss::SampleCornersKernel)
PSS_CUDA_KERNEL(pss::CrossEdgesKernel)
