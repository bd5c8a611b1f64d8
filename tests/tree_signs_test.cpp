// The signs along a tree that agree best with its nodes' votes (core/tree_signs.hpp), against
// every labelling of small random trees.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <random>
#include <vector>

#include "pss/core/error.hpp"
#include "pss/core/tree_signs.hpp"

namespace pss {
namespace {

std::int64_t cost_of(const SpanningTree& tree, const std::vector<std::int8_t>& votes, std::int64_t cut,
                     const std::vector<char>& turned) {
  std::int64_t cost = 0;
  for (std::size_t k = 0; k < votes.size(); ++k) {
    cost += turned[k] ? votes[k] : -votes[k];
    const int parent = tree.parent[k];
    if (parent >= 0 && turned[k] != turned[std::size_t(parent)]) cost += cut;
  }
  return cost;
}

// A random forest of n nodes: node k's parent is an earlier node or none, then the nodes shuffled
// into an order that keeps each parent before its children.
SpanningTree random_forest(int n, std::mt19937& rng) {
  SpanningTree tree;
  tree.parent.assign(std::size_t(n), -1);
  for (int k = 1; k < n; ++k)
    if (rng() % 5 != 0) tree.parent[std::size_t(k)] = int(rng() % unsigned(k));
  // Relabel by a random permutation, the order being the old indices' (parents first).
  std::vector<int> label(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k) label[std::size_t(k)] = k;
  std::shuffle(label.begin(), label.end(), rng);
  SpanningTree shuffled;
  shuffled.parent.assign(std::size_t(n), -1);
  for (int k = 0; k < n; ++k) {
    const int parent = tree.parent[std::size_t(k)];
    shuffled.parent[std::size_t(label[std::size_t(k)])] = parent < 0 ? -1 : label[std::size_t(parent)];
    shuffled.order.push_back(label[std::size_t(k)]);
  }
  return shuffled;
}

TEST(TreeSigns, TheLeastCostOfAnyLabelling) {
  std::mt19937 rng(11);
  for (int trial = 0; trial < 300; ++trial) {
    const int n = 1 + int(rng() % 11);
    const SpanningTree tree = random_forest(n, rng);
    std::vector<std::int8_t> votes(static_cast<std::size_t>(n));
    for (auto& v : votes) v = std::int8_t(int(rng() % 11) - 5);
    const std::int64_t cut = std::int64_t(rng() % 12);
    std::int64_t best = INT64_MAX;
    for (unsigned bits = 0; bits < (1u << n); ++bits) {
      std::vector<char> turned(static_cast<std::size_t>(n));
      for (int k = 0; k < n; ++k) turned[std::size_t(k)] = char((bits >> k) & 1);
      best = std::min(best, cost_of(tree, votes, cut, turned));
    }
    const std::vector<char> found = signs_along_tree(tree, votes, cut);
    ASSERT_EQ(cost_of(tree, votes, cut, found), best) << "trial " << trial << ", " << n << " nodes, cut " << cut;
  }
}

// A chain whose far half votes against: turned where the votes outweigh one cut, not where
// they do not; a tie keeps the root as it is and each child as its parent.
TEST(TreeSigns, AChainTurnsWhereItsVotesOutweighACut) {
  SpanningTree chain;
  for (int k = 0; k < 8; ++k) {
    chain.parent.push_back(k - 1);
    chain.order.push_back(k);
  }
  const std::vector<std::int8_t> votes = {3, 3, 3, 3, -2, -2, -2, -2};  // the far half turned: 16 less, 1 cut
  EXPECT_EQ(signs_along_tree(chain, votes, 15), (std::vector<char>{0, 0, 0, 0, 1, 1, 1, 1}));
  EXPECT_EQ(signs_along_tree(chain, votes, 17), (std::vector<char>{0, 0, 0, 0, 0, 0, 0, 0}));
  const std::vector<std::int8_t> against = {-1, -1, -1, -1, -1, -1, -1, -1};
  EXPECT_EQ(signs_along_tree(chain, against, 100), (std::vector<char>(8, 1)));
  EXPECT_EQ(signs_along_tree(chain, std::vector<std::int8_t>(8, 0), 1), (std::vector<char>(8, 0)));
  // Ties: the root kept or turned at the same cost (0), and so its child: both kept.
  SpanningTree pair;
  pair.parent = {-1, 0};
  pair.order = {0, 1};
  EXPECT_EQ(signs_along_tree(pair, std::vector<std::int8_t>{1, -1}, 2), (std::vector<char>{0, 0}));
}

TEST(TreeSigns, AnOrderThatIsNoTreesIsRefused) {
  SpanningTree tree;
  tree.parent = {-1, 0, 1};
  tree.order = {0, 2, 1};  // 2 before its parent 1
  const std::vector<std::int8_t> votes(3, 1);
  EXPECT_THROW(signs_along_tree(tree, votes, 1), Error);
  tree.order = {0, 1, 1};
  EXPECT_THROW(signs_along_tree(tree, votes, 1), Error);
  tree.order = {0, 1};
  EXPECT_THROW(signs_along_tree(tree, votes, 1), Error);
}

}  // namespace
}  // namespace pss
