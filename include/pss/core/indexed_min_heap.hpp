// A binary min-heap of the indices 0..n-1, each at most once, whose keys live outside it and
// only go down while it holds them (decrease-key): the frontier of Prim's tree
// (points/orient_normals.cpp). A queue of (key, index) pairs instead keeps every stale pair
// until it comes up: on a noisy cloud O(n) of them (issue 28). Host only.
#pragma once

#include <cstddef>
#include <vector>

namespace pss {

// Before(a, b): whether index a's key comes before b's; a strict total order.
template <class Before>
class IndexedMinHeap {
 public:
  IndexedMinHeap(std::size_t n, Before before) : before_(before), at_(n, -1) {}
  bool empty() const { return heap_.empty(); }
  // Adds i, or moves it up after its key went down.
  void lowered(int i) {
    int k = at_[std::size_t(i)];
    if (k < 0) {
      k = int(heap_.size());
      heap_.push_back(i);
    }
    up(k, i);
  }
  // Removes and returns the index whose key comes first.
  int pop() {
    const int top = heap_.front();
    at_[std::size_t(top)] = -1;
    const int last = heap_.back();
    heap_.pop_back();
    if (!heap_.empty()) down(0, last);
    return top;
  }

 private:
  void place(int k, int i) {
    heap_[std::size_t(k)] = i;
    at_[std::size_t(i)] = k;
  }
  void up(int k, int i) {
    while (k > 0 && before_(i, heap_[std::size_t((k - 1) / 2)])) {
      place(k, heap_[std::size_t((k - 1) / 2)]);
      k = (k - 1) / 2;
    }
    place(k, i);
  }
  void down(int k, int i) {
    const int size = int(heap_.size());
    for (;;) {
      int child = 2 * k + 1;
      if (child >= size) break;
      if (child + 1 < size && before_(heap_[std::size_t(child + 1)], heap_[std::size_t(child)])) ++child;
      if (!before_(heap_[std::size_t(child)], i)) break;
      place(k, heap_[std::size_t(child)]);
      k = child;
    }
    place(k, i);
  }

  Before before_;
  std::vector<int> at_;  // each index's place in heap_; -1 where it is not there
  std::vector<int> heap_;
};

}  // namespace pss
