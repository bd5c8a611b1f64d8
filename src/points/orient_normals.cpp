#include "pss/points/orient_normals.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <queue>
#include <vector>

#include "pss/core/progress.hpp"
#include "pss/points/turn_flipped_normals.hpp"
#include "pss/spatial/support_grid.hpp"

namespace pss {

void orient_normals_consistently(std::span<const vec3> points, std::span<vec3> normals, std::span<const float> radius) {
  const SupportGrid grid(points, radius, 1.0f);
  const SupportGridView view = grid.view();
  const std::span<const int> original = grid.original_index();

  std::vector<int> by_height(points.size());
  std::iota(by_height.begin(), by_height.end(), 0);
  std::stable_sort(by_height.begin(), by_height.end(), [&](int a, int b) { return points[a].z > points[b].z; });

  struct Edge {
    float cost;
    int node;
    int parent;  // oriented already; -1 for a seed
    bool operator>(const Edge& o) const { return cost > o.cost || (cost == o.cost && node > o.node); }
  };
  std::vector<char> done(points.size(), 0);
  // The cheapest edge queued to each point: one no cheaper is never the first to reach it,
  // and is not queued (Prim's queue held every edge: 5 GB at 10^7 points).
  std::vector<float> cheapest(points.size(), kInfinity);
  std::priority_queue<Edge, std::vector<Edge>, std::greater<>> frontier;
  // One thread: advancing once per 4096 points oriented keeps the atomic out of the inner loop.
  Progress progress("orient normals", std::int64_t(points.size()));
  std::size_t oriented = 0;
  for (int seed : by_height) {
    if (done[seed]) continue;
    if (normals[seed].z < 0) normals[seed] = -normals[seed];
    frontier.push({0.0f, seed, -1});
    while (!frontier.empty()) {
      const Edge e = frontier.top();
      frontier.pop();
      const int i = e.node;
      if (done[i]) continue;
      done[i] = 1;
      if (++oriented % 4096 == 0) progress.advance(4096);
      // Prim's order: the edge that reaches i first is its tree edge to the parent.
      if (e.parent >= 0 && glm::dot(normals[e.parent], normals[i]) < 0) normals[i] = -normals[i];
      view.for_each_covering(points[i], [&](vec3 q, float d2, int sorted) {
        const int j = original[sorted];
        if (done[j]) return;
        // Along the surface, not across it: a neighbour stacked above or below (the other
        // face of a thin part, whose normal is as parallel) is reached last.
        const float across = d2 > 0 ? std::abs(glm::dot(q - points[i], normals[i])) / std::sqrt(d2) : 0.0f;
        const float cost = 1.0f - std::abs(glm::dot(normals[i], normals[j])) + across;
        if (!(cost < cheapest[std::size_t(j)])) return;
        cheapest[std::size_t(j)] = cost;
        frontier.push({cost, j, i});
      });
    }
  }
  // The tree's signs are a guess across thin parts and creases (the bunny's ears: 1,123 of
  // its samples inward); turn the parts whose seams show it.
  std::vector<vec3> sorted(points.size());
  for (std::size_t k = 0; k < sorted.size(); ++k) sorted[k] = normals[std::size_t(original[k])];
  if (turn_flipped_normals(grid, sorted) == 0) return;
  for (std::size_t k = 0; k < sorted.size(); ++k) normals[std::size_t(original[k])] = sorted[k];
}

}  // namespace pss
