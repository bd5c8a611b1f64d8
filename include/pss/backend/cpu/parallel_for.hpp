// The CPU backend's launcher: f(i) for i in [0, n) on all cores. Dynamic scheduling in
// chunks, because per-item cost varies a lot (rays that miss, projections that iterate).
#pragma once

#include <atomic>
#include <cstdint>

#include "pss/core/cancel.hpp"
#include "pss/core/cpu_features.hpp"
#include "pss/core/progress.hpp"

// On x86-64 the items also run in a copy of the kernel compiled for AVX2, FMA and BMI2
// (core/cpu_features.hpp). GCC's `flatten` inlines the whole kernel into that copy, so no
// function shared with the baseline build is compiled for AVX2 (clang's inlines only the
// direct callees: slower, not wrong).
namespace pss::cpu {

namespace detail {

template <class F>
void run_items(F& f, std::int64_t begin, std::int64_t end) {
  for (std::int64_t i = begin; i < end; ++i) f(i);
}
#if PSS_CPU_AVX2
template <class F>
[[gnu::flatten, gnu::target("avx2,fma,bmi2")]] void run_items_avx2(
    F& f, std::int64_t begin, std::int64_t end) {
  for (std::int64_t i = begin; i < end; ++i) f(i);
}
#endif

}  // namespace detail

// Once the calling thread's cancel flag (core/cancel.hpp) is set, the chunks not yet begun
// skip their items.
template <class F>
void parallel_for(std::int64_t n, F&& f, Progress* progress = nullptr) {
  constexpr std::int64_t chunk = 256;
  const std::int64_t chunks = (n + chunk - 1) / chunk;
  const std::atomic<bool>* cancel = cancel_flag();  // the caller's: OpenMP's threads have none
  const bool avx2 = has_avx2();
#pragma omp parallel for schedule(dynamic, 1)
  for (std::int64_t c = 0; c < chunks; ++c) {
    if (cancel && cancel->load(std::memory_order_relaxed)) continue;
    const std::int64_t begin = c * chunk, end = begin + chunk < n ? begin + chunk : n;
#if PSS_CPU_AVX2
    if (avx2) detail::run_items_avx2(f, begin, end);
    else
#endif
      detail::run_items(f, begin, end);
    if (progress) progress->advance(end - begin);
  }
  (void)avx2;
}

}  // namespace pss::cpu
