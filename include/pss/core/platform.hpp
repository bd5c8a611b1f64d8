// The one portability header: everything that kernels share between the CPU and CUDA
// backends is marked PSS_HOST_DEVICE, and calls its math through the wrappers below, so
// algorithm code carries no #ifdef __CUDA_ARCH__.
#pragma once

#include <math.h>

#if defined(__CUDACC__)
#define PSS_HOST_DEVICE __host__ __device__
#else
#define PSS_HOST_DEVICE
#endif
#define PSS_INLINE PSS_HOST_DEVICE inline

namespace pss {

PSS_INLINE float sqrt(float x) { return ::sqrtf(x); }
PSS_INLINE float exp(float x) { return ::expf(x); }
PSS_INLINE float abs(float x) { return ::fabsf(x); }
PSS_INLINE float min(float a, float b) { return ::fminf(a, b); }
PSS_INLINE float max(float a, float b) { return ::fmaxf(a, b); }
PSS_INLINE float floor(float x) { return ::floorf(x); }
PSS_INLINE float pow(float x, float y) { return ::powf(x, y); }
PSS_INLINE float copysign(float x, float y) { return ::copysignf(x, y); }
PSS_INLINE int min(int a, int b) { return a < b ? a : b; }
PSS_INLINE int max(int a, int b) { return a > b ? a : b; }
PSS_INLINE float clamp(float x, float lo, float hi) { return min(max(x, lo), hi); }
PSS_INLINE int clamp(int x, int lo, int hi) { return min(max(x, lo), hi); }
PSS_INLINE bool is_finite(float x) { return isfinite(x); }

template <class T>
PSS_INLINE void swap(T& a, T& b) {
  T t = a;
  a = b;
  b = t;
}

inline constexpr float kInfinity = __builtin_huge_valf();

}  // namespace pss
