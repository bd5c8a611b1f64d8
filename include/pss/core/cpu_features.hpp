// Whether this build and this CPU have the AVX2 code paths: the CPU launcher's AVX2 copy of
// every kernel (backend/cpu/parallel_for.hpp) and the hand-written AVX2 voxel gather
// (volume/voxel_gather_avx2.hpp).
#pragma once

// On x86-64 with GCC or clang, kernels also run in a copy compiled for AVX2, FMA and BMI2
// (most x86 CPUs since 2013), chosen at run time: the build itself targets the baseline so
// that it runs anywhere. -DPSS_CPU_AVX2=0 leaves the AVX2 code out: every CPU then computes
// the baseline's bits. The inline kernels differ with it, so a program that compiles them
// must define it as the library was built.
#if !defined(PSS_CPU_AVX2)
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__CUDA_ARCH__)
#define PSS_CPU_AVX2 1
#else
#define PSS_CPU_AVX2 0
#endif
#endif

namespace pss::cpu {

// Whether this CPU runs the AVX2 code (PSS_CPU_AVX2), decided once.
inline bool has_avx2() {
#if PSS_CPU_AVX2
  static const bool yes = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma") &&
                          __builtin_cpu_supports("bmi2");
  return yes;
#else
  return false;
#endif
}

}  // namespace pss::cpu
