// The GPU code of the volumes' kernels (backend/cuda/launch.hpp): extraction and the frames
// of a volume. Their CPU code comes from the same headers, compiled by the host compiler
// where they are launched (extract.cpp, render_volume.cpp).
#include "pss/backend/cuda/launch.cuh"
#include "pss/render/frame_kernels.hpp"
#include "pss/volume/extract.hpp"
#include "pss/volume/render_volume.hpp"

PSS_CUDA_KERNEL(pss::ExtractCandidatesKernel)
PSS_CUDA_KERNEL(pss::PrimaryRaysKernel<pss::VolumeFinder>)
PSS_CUDA_KERNEL(pss::SecondaryRaysKernel<pss::VolumeFinder>)
PSS_CUDA_KERNEL(pss::ShadePixelsKernel<pss::VolumeFinder>)
