// Cooperative cancellation (core/cancel.hpp): the CPU backend's parallel_for skips the chunks
// it has not begun once the caller's flag is set, and only for the thread that installed it.
#include <gtest/gtest.h>

#include <atomic>
#include <thread>

#include "pss/backend/cpu/parallel_for.hpp"
#include "pss/core/cancel.hpp"

namespace pss {
namespace {

constexpr std::int64_t kItems = 256 * 1000;

std::int64_t run_counting(std::atomic<bool>* set_by_first_item = nullptr) {
  std::atomic<std::int64_t> count{0};
  cpu::parallel_for(kItems, [&](std::int64_t i) {
    if (i == 0 && set_by_first_item) set_by_first_item->store(true);
    count.fetch_add(1, std::memory_order_relaxed);
  });
  return count.load();
}

TEST(Cancel, WithoutAFlagEveryItemRuns) {
  EXPECT_EQ(cancel_flag(), nullptr);
  EXPECT_EQ(run_counting(), kItems);
  const std::atomic<bool> clear{false};
  const CancelScope scope(&clear);
  EXPECT_EQ(run_counting(), kItems);
}

TEST(Cancel, ASetFlagSkipsTheChunksNotBegun) {
  const std::atomic<bool> set{true};
  {
    const CancelScope scope(&set);
    EXPECT_EQ(run_counting(), 0);
  }
  std::atomic<bool> later{false};
  const CancelScope scope(&later);
  // Set by the first item: only the chunks already running finish (one per thread at most,
  // as scheduling is dynamic, one chunk at a time).
  const std::int64_t ran = run_counting(&later);
  EXPECT_GT(ran, 0);
  EXPECT_LE(ran, 256 * 64);
}

TEST(Cancel, ScopesNestAndBelongToTheirThread) {
  const std::atomic<bool> outer{true}, inner{false};
  const CancelScope a(&outer);
  {
    const CancelScope b(&inner);
    EXPECT_EQ(cancel_flag(), &inner);
    EXPECT_EQ(run_counting(), kItems);
  }
  EXPECT_EQ(cancel_flag(), &outer);
  std::int64_t elsewhere = -1;
  std::thread([&] { elsewhere = run_counting(); }).join();  // another thread: no flag
  EXPECT_EQ(elsewhere, kItems);
}

}  // namespace
}  // namespace pss
