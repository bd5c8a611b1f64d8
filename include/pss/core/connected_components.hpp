// Connected components of a graph whose edges any number of threads join at once (host
// only): the chains of a cloud sampled in rows (src/points/rows.cpp), the patches of
// agreeing normals (src/points/turn_flipped_normals.cpp), a mesh's components and the fans
// about its vertices (src/mesh/incidence.hpp).
#pragma once

#include <atomic>
#include <cstddef>
#include <utility>
#include <vector>

namespace pss {

// A union-find whose joins may run concurrently. A root is only ever linked under a smaller
// index, so each component's root is its least member whatever the order of the joins: the
// labels are the same for any thread count. Index: int, or a wider type for more members.
template <class Index = int>
class ConnectedComponents {
 public:
  explicit ConnectedComponents(std::size_t n) : parent_(n) {
    for (std::size_t i = 0; i < n; ++i) parent_[i].store(Index(i), std::memory_order_relaxed);
  }
  // The least member of i's component (once the joins are done; any member's root before).
  Index find(Index i) {
    for (;;) {
      Index p = parent_[std::size_t(i)].load(std::memory_order_acquire);
      if (p == i) return i;
      const Index grandparent = parent_[std::size_t(p)].load(std::memory_order_acquire);
      if (grandparent != p) parent_[std::size_t(i)].compare_exchange_weak(p, grandparent, std::memory_order_acq_rel);
      i = p;
    }
  }
  void join(Index a, Index b) {
    for (;;) {
      a = find(a);
      b = find(b);
      if (a == b) return;
      if (a < b) std::swap(a, b);
      Index root = a;
      if (parent_[std::size_t(a)].compare_exchange_strong(root, b, std::memory_order_acq_rel)) return;
    }
  }

 private:
  std::vector<std::atomic<Index>> parent_;
};

}  // namespace pss
