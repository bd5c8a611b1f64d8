// The signs along a tree that agree best with votes at its nodes (visibility.hpp: which way
// a spanning tree's normals face). Each node is kept (+) or turned (−); a node with vote v
// costs −v kept and +v turned, and each edge whose two ends differ costs `cut`. The least
// total is found exactly by dynamic programming, leaves to root and back: O(nodes).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace pss {

// A forest's edges: each node's parent (−1 at a root) and the nodes in an order where a
// parent comes before its children (the order a spanning tree reached them).
struct SpanningTree {
  std::vector<int> parent;
  std::vector<int> order;
};

// Per node, 1 where it is turned. Ties keep a root as it is and a child as its parent.
// Throws Error unless parent, order and votes are as long and order lists each node once,
// after its parent.
std::vector<char> signs_along_tree(const SpanningTree& tree, std::span<const std::int8_t> votes, std::int64_t cut);

}  // namespace pss
