#include "pss/points/orient_normals.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <vector>

#include "pss/core/indexed_min_heap.hpp"
#include "pss/core/progress.hpp"
#include "pss/spatial/support_grid.hpp"

namespace pss {

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
  // The points the tree may reach next, by their cheapest edge's cost, then input index.
  IndexedMinHeap frontier(n, [&](int a, int b) {
    const float ca = cheapest[std::size_t(a)], cb = cheapest[std::size_t(b)];
    return ca < cb || (ca == cb && original[std::size_t(a)] < original[std::size_t(b)]);
  });
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
  for (std::size_t k = 0; k < n; ++k) normals[std::size_t(original[k])] = sorted[k];
}

}  // namespace pss
