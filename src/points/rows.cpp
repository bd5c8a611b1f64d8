#include "rows.hpp"

#include <algorithm>
#include <cmath>

#include "pss/backend/cpu/parallel_for.hpp"
#include "pss/core/connected_components.hpp"

namespace pss::points_detail {

namespace {

constexpr int kLinks = 4;  // the nearest neighbours a sample is chained to

// The chains: the parts of the graph that links each sample to its kLinks nearest. On a
// row those lie along it, so rows farther apart than kLinks steps stay apart; a surface
// sampled in two dimensions is one part.
std::vector<unsigned> chains(std::span<const vec3> unit, const KdTree& tree) {
  const std::size_t n = unit.size();
  ConnectedComponents chained(n);
  parallel_for_in_tree_order(tree, [&](std::int64_t i) {
    unsigned index[kLinks + 1] = {};
    float d2[kLinks + 1] = {};
    const std::size_t found = tree.knnSearch(&unit[std::size_t(i)].x, kLinks + 1, index, d2);
    for (std::size_t j = 1; j < found; ++j) chained.join(int(i), int(index[j]));
  });
  std::vector<unsigned> chain(n);
  cpu::parallel_for(std::int64_t(n), [&](std::int64_t i) { chain[std::size_t(i)] = unsigned(chained.find(int(i))); });
  return chain;
}

}  // namespace

std::vector<float> row_gaps(std::span<const vec3> unit, const KdTree& tree, std::span<const float> kth,
                            std::span<const float> wide) {
  const std::size_t n = unit.size();
  // Fewer samples than two rows: a cloud of rows needs more than one.
  if (n < 2 * std::size_t(kRowLength)) return {};
  const auto most = [n](const std::vector<char>& flags) {
    return 2 * std::count(flags.begin(), flags.end(), 1) >= std::ptrdiff_t(n);
  };
  std::vector<char> on_row(n);
  for (std::size_t i = 0; i < n; ++i) on_row[i] = wide[i] > kRowGrowth * kth[i];
  if (!most(on_row)) return {};  // the usual case, before any chain is built
  const std::vector<unsigned> chain = chains(unit, tree);
  std::vector<unsigned> size(n, 0);
  for (unsigned c : chain) ++size[c];
  for (std::size_t i = 0; i < n; ++i) on_row[i] = on_row[i] && size[chain[i]] >= unsigned(kRowLength);
  if (!most(on_row)) return {};

  std::vector<float> gap(n, 0.0f);
  parallel_for_in_tree_order(tree, [&](std::int64_t s) {
    const auto i = std::size_t(s);
    if (!on_row[i]) return;
    constexpr std::size_t kFarthest = 512;
    unsigned index[kFarthest];
    float d2[kFarthest];
    for (const std::size_t k : {std::size_t(64), kFarthest}) {
      const std::size_t found = tree.knnSearch(&unit[i].x, std::min(k, n), index, d2);
      for (std::size_t j = 1; j < found; ++j)
        if (chain[index[j]] != chain[i]) {
          gap[i] = std::sqrt(d2[j]);
          return;
        }
    }
  });
  return gap;
}

}  // namespace pss::points_detail
