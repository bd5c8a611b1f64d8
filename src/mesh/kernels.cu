// The GPU code of the mesh's kernels (backend/cuda/launch.hpp); their CPU code comes from the
// same headers, compiled where they are launched (mesh_cloud.cpp, mesh_volume.cpp).
#include "pss/backend/cuda/launch.cuh"
#include "pss/mesh/cloud_implicit.hpp"
#include "pss/mesh/volume_implicit.hpp"

PSS_CUDA_KERNEL(pss::SampleCornersKernel<pss::CloudImplicit>)
PSS_CUDA_KERNEL(pss::CrossEdgesKernel<pss::CloudImplicit>)
PSS_CUDA_KERNEL(pss::SampleCornersKernel<pss::VolumeImplicit>)
PSS_CUDA_KERNEL(pss::CrossEdgesKernel<pss::VolumeImplicit>)
