#include "pss/tiles/orient.hpp"

#include <algorithm>
#include <cstdlib>
#include <limits>
#include <numeric>

#include "pss/core/error.hpp"

namespace pss {

std::uint32_t PieceSigns::add_piece(float z, std::uint64_t root, const FacingVote& vote) {
  if (roots_.size() >= std::size_t(std::numeric_limits<std::uint32_t>::max()))
    throw Error("the normals' orientation has more than 2^32 pieces across its tiles");
  roots_.push_back({z, root});
  facing_.push_back(vote);
  return std::uint32_t(roots_.size() - 1);
}

void PieceSigns::vote(std::uint32_t a, std::uint32_t b, bool alike) {
  if (a == b) return;
  if (a > b) std::swap(a, b);
  votes_[(std::uint64_t(a) << 32) | b] += alike ? 1 : -1;
}

std::vector<char> PieceSigns::turns() const {
  // The strongest agreements first, then by the pieces' numbers: the same forest every run.
  std::vector<std::pair<std::uint64_t, std::int64_t>> votes(votes_.begin(), votes_.end());
  std::sort(votes.begin(), votes.end(), [](const auto& x, const auto& y) {
    const std::int64_t sx = std::llabs(x.second), sy = std::llabs(y.second);
    return sx > sy || (sx == sy && x.first < y.first);
  });
  // Union-find with each piece's sign relative to its parent's.
  const std::size_t n = roots_.size();
  std::vector<std::uint32_t> parent(n);
  std::iota(parent.begin(), parent.end(), 0u);
  std::vector<char> against(n, 0);
  auto find = [&](std::uint32_t x) {  // the root, with against[x] made relative to it
    std::uint32_t root = x;
    char sign = 0;
    while (parent[root] != root) {
      sign ^= against[root];
      root = parent[root];
    }
    // Compress: each on the path points at the root, its sign relative to it.
    while (parent[x] != root) {
      const std::uint32_t next = parent[x];
      const char next_sign = char(sign ^ against[x]);
      against[x] = sign;
      parent[x] = root;
      x = next;
      sign = next_sign;
    }
    return root;
  };
  for (const auto& [key, balance] : votes) {
    if (balance == 0) continue;  // no say either way
    const auto a = std::uint32_t(key >> 32), b = std::uint32_t(key & 0xffffffffu);
    const std::uint32_t ra = find(a), rb = find(b);
    if (ra == rb) continue;
    // against[a] ^ against[b] ^ (a and b face apart) is rb's sign relative to ra.
    parent[rb] = ra;
    against[rb] = char(against[a] ^ against[b] ^ (balance < 0 ? 1 : 0));
  }
  // Each part keeps the sign of its piece grown from its highest point (ties by index).
  std::vector<std::uint32_t> top(n, std::uint32_t(-1));
  for (std::uint32_t p = 0; p < n; ++p) {
    const std::uint32_t r = find(p);
    std::uint32_t& t = top[r];
    if (t == std::uint32_t(-1) || roots_[p].z > roots_[t].z ||
        (roots_[p].z == roots_[t].z && roots_[p].index < roots_[t].index))
      t = p;
  }
  std::vector<char> turn(n);
  std::vector<FacingVote> facing(n);  // by each part's root in the forest
  for (std::uint32_t p = 0; p < n; ++p) {
    const std::uint32_t r = find(p);
    turn[p] = char(against[p] ^ against[top[r]]);
    facing[r].add(facing_[p], turn[p]);
  }
  std::vector<char> inward(n);  // by each part's root
  for (std::uint32_t r = 0; r < n; ++r) inward[r] = facing[r].sign() < 0;
  for (std::uint32_t p = 0; p < n; ++p) turn[p] ^= inward[find(p)];
  return turn;
}

}  // namespace pss
