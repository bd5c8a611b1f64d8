#include "pss/core/tree_signs.hpp"

#include <algorithm>
#include <array>

#include "pss/core/error.hpp"

namespace pss {

namespace {

void check_tree(const SpanningTree& tree, std::size_t n) {
  if (tree.parent.size() != n || tree.order.size() != n) throw Error("tree signs: one parent and one vote per node");
  std::vector<char> seen(n, 0);
  for (const int i : tree.order) {
    if (i < 0 || std::size_t(i) >= n || seen[std::size_t(i)])
      throw Error("tree signs: the order must list each node once");
    const int parent = tree.parent[std::size_t(i)];
    if (parent >= 0 && (std::size_t(parent) >= n || !seen[std::size_t(parent)]))
      throw Error("tree signs: a node's parent must come before it");
    seen[std::size_t(i)] = 1;
  }
}

}  // namespace

std::vector<char> signs_along_tree(const SpanningTree& tree, std::span<const std::int8_t> votes, std::int64_t cut) {
  const std::size_t n = votes.size();
  check_tree(tree, n);
  // cost[k][s]: the least cost of k's subtree with k kept (s = 0) or turned (s = 1).
  std::vector<std::array<std::int64_t, 2>> cost(n, {0, 0});
  for (auto it = tree.order.rbegin(); it != tree.order.rend(); ++it) {
    const auto k = std::size_t(*it);
    cost[k][0] -= votes[k];
    cost[k][1] += votes[k];
    const int parent = tree.parent[k];
    if (parent < 0) continue;
    auto& above = cost[std::size_t(parent)];
    above[0] += std::min(cost[k][0], cost[k][1] + cut);
    above[1] += std::min(cost[k][1], cost[k][0] + cut);
  }
  std::vector<char> turned(n, 0);
  for (const int i : tree.order) {
    const auto k = std::size_t(i);
    const int parent = tree.parent[k];
    if (parent < 0) {
      turned[k] = cost[k][1] < cost[k][0];
      continue;
    }
    const int as_parent = turned[std::size_t(parent)];
    turned[k] = char(cost[k][1 - as_parent] + cut < cost[k][as_parent] ? 1 - as_parent : as_parent);
  }
  return turned;
}

}  // namespace pss
