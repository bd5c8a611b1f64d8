#include "rows.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "pss/backend/cpu/parallel_for.hpp"

namespace pss::points_detail {

namespace {

constexpr int kLinks = 4;  // the nearest neighbours a sample is chained to

// The chains: the parts of the graph that links each sample to its kLinks nearest. On a
// row those lie along it, so rows farther apart than kLinks steps stay apart; a surface
// sampled in two dimensions is one part.
std::vector<unsigned> chains(std::span<const vec3> unit, const KdTree& tree) {
  const std::size_t n = unit.size();
  std::vector<unsigned> link(n * kLinks, unsigned(-1));
  cpu::parallel_for(std::int64_t(n), [&](std::int64_t i) {
    unsigned index[kLinks + 1] = {};
    float d2[kLinks + 1] = {};
    const std::size_t found = tree.knnSearch(&unit[std::size_t(i)].x, kLinks + 1, index, d2);
    for (std::size_t j = 1; j < found; ++j) link[std::size_t(i) * kLinks + j - 1] = index[j];
  });
  std::vector<unsigned> parent(n);
  std::iota(parent.begin(), parent.end(), 0u);
  const auto root = [&](unsigned i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  for (std::size_t i = 0; i < n; ++i)
    for (int j = 0; j < kLinks; ++j) {
      const unsigned other = link[i * kLinks + std::size_t(j)];
      if (other == unsigned(-1)) continue;
      const unsigned a = root(unsigned(i)), b = root(other);
      if (a != b) parent[std::max(a, b)] = std::min(a, b);
    }
  for (std::size_t i = 0; i < n; ++i) parent[i] = root(unsigned(i));
  return parent;
}

}  // namespace

std::vector<float> row_gaps(std::span<const vec3> unit, const KdTree& tree, std::span<const float> kth) {
  const std::size_t n = unit.size();
  if (n < 2 * std::size_t(kRowLength)) return {};
  const std::vector<unsigned> chain = chains(unit, tree);
  std::vector<unsigned> size(n, 0);
  for (unsigned c : chain) ++size[c];
  constexpr int kWide = 30;
  std::vector<char> on_row(n, 0);
  cpu::parallel_for(std::int64_t(n), [&](std::int64_t s) {
    const auto i = std::size_t(s);
    if (size[chain[i]] < unsigned(kRowLength)) return;
    unsigned index[kWide + 1];
    float d2[kWide + 1];
    const std::size_t found = tree.knnSearch(&unit[i].x, kWide + 1, index, d2);
    on_row[i] = found == kWide + 1 && std::sqrt(d2[kWide]) > kRowGrowth * kth[i];
  });
  if (2 * std::count(on_row.begin(), on_row.end(), 1) < std::ptrdiff_t(n)) return {};

  std::vector<float> gap(n, 0.0f);
  cpu::parallel_for(std::int64_t(n), [&](std::int64_t s) {
    const auto i = std::size_t(s);
    if (!on_row[i]) return;
    std::vector<unsigned> index;
    std::vector<float> d2;
    for (const std::size_t k : {std::size_t(64), std::size_t(512)}) {
      index.resize(std::min(k, n));
      d2.resize(index.size());
      const std::size_t found = tree.knnSearch(&unit[i].x, index.size(), index.data(), d2.data());
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
