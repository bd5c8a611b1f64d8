// The CPU backend's launcher: f(i) for i in [0, n) on all cores. Dynamic scheduling in
// chunks, because per-item cost varies a lot (rays that miss, projections that iterate).
#pragma once

#include <cstdint>

#include "pss/core/cancel.hpp"
#include "pss/core/progress.hpp"

namespace pss::cpu {

// Once the calling thread's cancel flag (core/cancel.hpp) is set, the chunks not yet begun
// skip their items.
template <class F>
void parallel_for(std::int64_t n, F&& f, Progress* progress = nullptr) {
  constexpr std::int64_t chunk = 256;
  const std::int64_t chunks = (n + chunk - 1) / chunk;
  const std::atomic<bool>* cancel = cancel_flag();  // the caller's: OpenMP's threads have none
#pragma omp parallel for schedule(dynamic, 1)
  for (std::int64_t c = 0; c < chunks; ++c) {
    if (cancel && cancel->load(std::memory_order_relaxed)) continue;
    const std::int64_t end = c * chunk + chunk < n ? c * chunk + chunk : n;
    for (std::int64_t i = c * chunk; i < end; ++i) f(i);
    if (progress) progress->advance(end - c * chunk);
  }
}

}  // namespace pss::cpu
