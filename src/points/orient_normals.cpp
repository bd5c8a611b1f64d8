#include "pss/points/orient_normals.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <vector>

#include "pss/core/progress.hpp"
#include "pss/points/turn_flipped_normals.hpp"
#include "pss/spatial/support_grid.hpp"

namespace pss {

namespace {

// The points Prim's tree may reach next, each at most once, keyed by its cheapest edge's cost
// and then its input index: a cheaper edge moves its point up (decrease-key). A queue of
// edges instead holds the stale ones too: on a noisy cloud, whose normals make many edges
// about as cheap, O(n) of them (1.3 GB at 10^7 points; issue 28).
class Frontier {
 public:
  Frontier(std::span<const float> cost, std::span<const int> tie) : cost_(cost), tie_(tie), at_(cost.size(), -1) {}
  bool empty() const { return heap_.empty(); }
  // After cost[node] went down, or as the node joins.
  void lowered(int node) {
    int k = at_[std::size_t(node)];
    if (k < 0) {
      k = int(heap_.size());
      heap_.push_back(node);
    }
    up(k, node);
  }
  int pop() {
    const int top = heap_.front();
    at_[std::size_t(top)] = -1;
    const int last = heap_.back();
    heap_.pop_back();
    if (!heap_.empty()) down(0, last);
    return top;
  }

 private:
  bool before(int a, int b) const {
    const float ca = cost_[std::size_t(a)], cb = cost_[std::size_t(b)];
    return ca < cb || (ca == cb && tie_[std::size_t(a)] < tie_[std::size_t(b)]);
  }
  void place(int k, int node) {
    heap_[std::size_t(k)] = node;
    at_[std::size_t(node)] = k;
  }
  void up(int k, int node) {
    while (k > 0 && before(node, heap_[std::size_t((k - 1) / 2)])) {
      place(k, heap_[std::size_t((k - 1) / 2)]);
      k = (k - 1) / 2;
    }
    place(k, node);
  }
  void down(int k, int node) {
    const int size = int(heap_.size());
    for (;;) {
      int child = 2 * k + 1;
      if (child >= size) break;
      if (child + 1 < size && before(heap_[std::size_t(child + 1)], heap_[std::size_t(child)])) ++child;
      if (!before(heap_[std::size_t(child)], node)) break;
      place(k, heap_[std::size_t(child)]);
      k = child;
    }
    place(k, node);
  }

  std::span<const float> cost_;
  std::span<const int> tie_;
  std::vector<int> at_;  // each point's place in heap_; -1 where it is not there
  std::vector<int> heap_;
};

}  // namespace

void orient_normals_consistently(std::span<const vec3> points, std::span<vec3> normals, std::span<const float> radius) {
  const SupportGrid grid(points, radius, 1.0f);
  const SupportGridView view = grid.view();
  const std::span<const int> original = grid.original_index();
  // The tree grows in the grid's order, where a point's neighbours lie near it in memory.
  // Ties go by input order, so the tree is the one that order gives.
  const std::span<const vec3> at = grid.sorted_points();
  const std::size_t n = at.size();
  std::vector<vec3> sorted(n);
  for (std::size_t k = 0; k < n; ++k) sorted[k] = normals[std::size_t(original[k])];

  std::vector<int> by_height(n);
  std::iota(by_height.begin(), by_height.end(), 0);
  std::sort(by_height.begin(), by_height.end(),
            [&](int a, int b) { return at[a].z > at[b].z || (at[a].z == at[b].z && original[a] < original[b]); });

  std::vector<char> done(n, 0);
  std::vector<float> cheapest(n, kInfinity);  // the cheapest edge yet from the tree to each point
  std::vector<int> parent(n, -1);             // its end in the tree; -1 for a seed
  Frontier frontier(cheapest, original);
  // One thread: advancing once per 4096 points oriented keeps the atomic out of the inner loop.
  Progress progress("orient normals", std::int64_t(n));
  std::size_t oriented = 0;
  for (int seed : by_height) {
    if (done[seed]) continue;
    if (sorted[seed].z < 0) sorted[seed] = -sorted[seed];
    cheapest[std::size_t(seed)] = 0;
    frontier.lowered(seed);
    while (!frontier.empty()) {
      const int i = frontier.pop();
      done[i] = 1;
      if (++oriented % 4096 == 0) progress.advance(4096);
      // Prim's order: the cheapest edge to i when it is reached is its tree edge.
      const int from = parent[std::size_t(i)];
      if (from >= 0 && glm::dot(sorted[from], sorted[i]) < 0) sorted[i] = -sorted[i];
      view.for_each_covering(at[i], [&](vec3 q, float d2, int j) {
        if (done[j]) return;
        // Along the surface, not across it: a neighbour stacked above or below (the other
        // face of a thin part, whose normal is as parallel) is reached last.
        const float across = d2 > 0 ? std::abs(glm::dot(q - at[i], sorted[i])) / std::sqrt(d2) : 0.0f;
        const float cost = 1.0f - std::abs(glm::dot(sorted[i], sorted[j])) + across;
        if (!(cost < cheapest[std::size_t(j)])) return;
        cheapest[std::size_t(j)] = cost;
        parent[std::size_t(j)] = i;
        frontier.lowered(j);
      });
    }
  }
  // The tree's signs are a guess across thin parts and creases (the bunny's ears: 1,123 of
  // its samples inward); turn the parts whose seams show it.
  turn_flipped_normals(grid, sorted);
  for (std::size_t k = 0; k < n; ++k) normals[std::size_t(original[k])] = sorted[k];
}

}  // namespace pss
