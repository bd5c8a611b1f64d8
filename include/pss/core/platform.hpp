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

// Sums over a neighbourhood run in this many independent lanes on the CPU, lane l taking
// the terms l, l + lanes, …: each lane is its own sum, so compilers put the lanes in SIMD
// registers without reassociating anything. One on the GPU, where a thread is a lane.
#if defined(__CUDA_ARCH__)
#define PSS_SUM_LANES 1
#else
#define PSS_SUM_LANES 8
#endif

// Before a loop whose body a GPU kernel must hold once (a finder's search, whose stack
// would be counted per copy): nvcc unrolls short constant loops otherwise.
#if defined(__CUDA_ARCH__)
#define PSS_NO_UNROLL _Pragma("unroll 1")
#else
#define PSS_NO_UNROLL
#endif

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

// e^x for finite x ≤ 0, as Cephes' expf computes it: x = k·ln 2 + r, |r| ≤ ln 2 / 2, a
// degree-5 polynomial for e^r, and 2^k put in the exponent bits. Within 1 ulp of e^x down
// to x = −87 (tested); below, where e^x leaves the normal floats, a value under 2⁻¹²⁵.
// Unlike libm's expf it has no branch and no call, so loops of Gaussian weights run in
// SIMD lanes (a clamp of x, rather than of k, stops GCC vectorising). CUDA's expf is
// already inline.
PSS_INLINE float exp_nonpositive(float x) {
#if defined(__CUDA_ARCH__)
  return ::expf(x);
#else
  // k = round(x / ln 2) by the 1.5·2²³ trick (exact for |k| < 2²²; vectorises, unlike rintf).
  const float k = (x * 1.44269504f + 12582912.0f) - 12582912.0f;
  const float r = (x - k * 0.693359375f) + k * 2.12194440e-4f;  // ln 2 in two parts
  float p = 1.9875691500e-4f;
  p = p * r + 1.3981999507e-3f;
  p = p * r + 8.3334519073e-3f;
  p = p * r + 4.1665795894e-2f;
  p = p * r + 1.6666665459e-1f;
  p = p * r + 5.0000001201e-1f;
  const float er = p * r * r + r + 1.0f;
  int exponent = int(k);
  exponent = exponent > -126 ? exponent : -126;
  return er * __builtin_bit_cast(float, (exponent + 127) << 23);
#endif
}

template <class T>
PSS_INLINE void swap(T& a, T& b) {
  T t = a;
  a = b;
  b = t;
}

inline constexpr float kInfinity = __builtin_huge_valf();

}  // namespace pss
