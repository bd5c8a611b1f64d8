// Connected components of a graph whose edges all threads join at once (host only): the
// chains of rows.cpp and the patches of turn_flipped_normals.cpp. Internal to src/points.
#pragma once

#include <atomic>
#include <cstddef>
#include <utility>
#include <vector>

namespace pss::points_detail {

// A union-find whose joins may run concurrently. A root is only ever linked under a smaller
// index, so each component's root is its least member whatever the order of the joins: the
// labels are the same for any thread count.
class Components {
 public:
  explicit Components(std::size_t n) : parent_(n) {
    for (std::size_t i = 0; i < n; ++i) parent_[i].store(int(i), std::memory_order_relaxed);
  }
  // The least member of i's component (once the joins are done; any member's root before).
  int find(int i) {
    for (;;) {
      int p = parent_[std::size_t(i)].load(std::memory_order_acquire);
      if (p == i) return i;
      const int grandparent = parent_[std::size_t(p)].load(std::memory_order_acquire);
      if (grandparent != p) parent_[std::size_t(i)].compare_exchange_weak(p, grandparent, std::memory_order_acq_rel);
      i = p;
    }
  }
  void join(int a, int b) {
    for (;;) {
      a = find(a);
      b = find(b);
      if (a == b) return;
      if (a < b) std::swap(a, b);
      int root = a;
      if (parent_[std::size_t(a)].compare_exchange_strong(root, b, std::memory_order_acq_rel)) return;
    }
  }

 private:
  std::vector<std::atomic<int>> parent_;
};

}  // namespace pss::points_detail
