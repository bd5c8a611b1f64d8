// The frontier of the orientation's Prim tree (core/indexed_min_heap.hpp): against a brute
// force that scans every index it holds.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "pss/core/indexed_min_heap.hpp"

namespace pss {
namespace {

// Keys drawn from few values, so that ties (broken by index) are common; keys only go down
// while held, and an index popped may come back with a new key, as in Prim's loop.
TEST(IndexedMinHeap, PopsWhatABruteForceFindsFirstThroughDecreasesAndReturns) {
  std::mt19937 rng(5);
  for (const int n : {1, 2, 17, 300}) {
    std::vector<float> key(std::size_t(n), 0.0f);
    std::vector<char> held(std::size_t(n), 0);
    auto before = [&](int a, int b) {
      return key[std::size_t(a)] < key[std::size_t(b)] || (key[std::size_t(a)] == key[std::size_t(b)] && a < b);
    };
    IndexedMinHeap heap(std::size_t(n), before);
    std::uniform_int_distribution<int> pick(0, n - 1), value(0, 9), action(0, 3);
    int pops = 0;
    for (int step = 0; step < 40 * n; ++step) {
      const int i = pick(rng);
      if (action(rng) > 0) {  // add i, or lower its key
        const float k = float(value(rng));
        if (held[std::size_t(i)] && !(k < key[std::size_t(i)])) continue;
        key[std::size_t(i)] = k;
        held[std::size_t(i)] = 1;
        heap.lowered(i);
      } else if (!heap.empty()) {
        int first = -1;
        for (int j = 0; j < n; ++j)
          if (held[std::size_t(j)] && (first < 0 || before(j, first))) first = j;
        ASSERT_EQ(heap.pop(), first) << "n " << n << " step " << step;
        held[std::size_t(first)] = 0;
        ++pops;
      }
      bool any = false;
      for (char h : held) any = any || h;
      ASSERT_EQ(heap.empty(), !any);
    }
    EXPECT_GT(pops, n);  // pops and returns both happened
  }
}

}  // namespace
}  // namespace pss
