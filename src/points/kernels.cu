// The GPU code of the point clouds' kernels (backend/cuda/launch.hpp): projection, local
// polynomials and the frames of a cloud. Their CPU code comes from the same headers, compiled
// by the host compiler where they are launched (project_cloud.cpp, render_cloud.cpp).
#include "pss/backend/cuda/launch.cuh"
#include "pss/points/local_polynomials.hpp"
#include "pss/points/outliers.hpp"
#include "pss/points/project_points.hpp"
#include "pss/points/render_cloud.hpp"
#include "pss/render/frame_kernels.hpp"

// The primary rays at 127 registers or fewer: four blocks of 128 per SM, not three (their
// frames 3-6 % faster on an H100, docs/benchmarks.md).
template <>
inline constexpr int pss::cuda::kMinBlocksPerSm<pss::PrimaryRaysKernel<pss::PointFinder>> = 4;

PSS_CUDA_KERNEL(pss::ProjectPointsKernel)
PSS_CUDA_KERNEL(pss::FitLocalPolynomialsKernel)
PSS_CUDA_KERNEL(pss::OutlierDistanceKernel)
PSS_CUDA_KERNEL(pss::PrimaryRaysKernel<pss::PointFinder>)
PSS_CUDA_KERNEL(pss::SecondaryRaysKernel<pss::PointFinder>)
PSS_CUDA_KERNEL(pss::ShadePixelsKernel<pss::PointFinder>)
