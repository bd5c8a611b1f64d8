// The CPU backend runs its kernels in the AVX2 copy wherever the CPU has AVX2, FMA and BMI2
// (backend/cpu/parallel_for.hpp). What tells the copies apart from the outside is rounding:
// there GCC contracts a·b − c into one FMA, which rounds once. With a = b = 1 + 2⁻¹², c = 1 + 2⁻¹¹
// the exact a·b − c is 2⁻²⁴; a product rounded first (to even) leaves 0.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "pss/backend/cpu/parallel_for.hpp"

namespace pss {
namespace {

// Whether /proc/cpuinfo lists every flag the AVX2 copy needs, as the kernel sees the CPU;
// nothing when it cannot be read.
std::optional<bool> cpuinfo_lists_avx2() {
  std::ifstream in("/proc/cpuinfo");
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("flags", 0) != 0) continue;
    std::istringstream words(line.substr(line.find(':') + 1));
    bool avx2 = false, fma = false, bmi2 = false;
    for (std::string w; words >> w;) {
      avx2 = avx2 || w == "avx2";
      fma = fma || w == "fma";
      bmi2 = bmi2 || w == "bmi2";
    }
    return avx2 && fma && bmi2;
  }
  return std::nullopt;
}

TEST(CpuDispatch, KernelsRunInTheAvx2CopyWhereTheCpuHasIt) {
#if !PSS_CPU_AVX2 || !defined(__linux__)
  GTEST_SKIP() << "not an x86-64 GCC build on Linux";
#else
  const std::optional<bool> listed = cpuinfo_lists_avx2();
  if (!listed) GTEST_SKIP() << "/proc/cpuinfo has no flags line";
  const bool avx2 = *listed;
  EXPECT_EQ(cpu::has_avx2(), avx2);
  const float one_step = std::ldexp(1.0f, -12);
  std::vector<float> a(1000, 1 + one_step), c(1000, 1 + 2 * one_step), out(1000, -1);
  cpu::parallel_for(std::int64_t(out.size()), [&](std::int64_t i) { out[i] = a[i] * a[i] - c[i]; });
  const float expected = avx2 ? std::ldexp(1.0f, -24) : 0.0f;
  for (float x : out) ASSERT_EQ(x, expected) << (avx2 ? "the AVX2 copy did not run" : "an FMA without AVX2");
#endif
}

}  // namespace
}  // namespace pss
