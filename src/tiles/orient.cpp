#include "pss/tiles/orient.hpp"

#include <algorithm>
#include <cstdlib>
#include <limits>
#include <numeric>

#include "pss/core/connected_components.hpp"
#include "pss/core/error.hpp"
#include "pss/points/visibility.hpp"

namespace pss {

std::uint32_t PieceSigns::add_piece(float z, std::uint64_t root, const FacingVote& vote, const PieceRays& rays) {
  if (roots_.size() >= std::size_t(std::numeric_limits<std::uint32_t>::max()))
    throw Error("the normals' orientation has more than 2^32 pieces across its tiles");
  roots_.push_back({z, root});
  facing_.push_back(vote);
  rays_.push_back(rays);
  return std::uint32_t(roots_.size() - 1);
}

void PieceSigns::vote(std::uint32_t a, std::uint32_t b, bool alike, bool a_seen, bool b_seen) {
  if (a == b) return;
  if (a > b) {
    std::swap(a, b);
    std::swap(a_seen, b_seen);
  }
  std::array<std::int64_t, 2>& balance = votes_[(std::uint64_t(a) << 32) | b];
  balance[0] += alike ? 1 : -1;
  balance[1] += alike != (a_seen != b_seen) ? 1 : -1;
}

PieceTurns PieceSigns::turns() const {
  const std::size_t n = roots_.size();
  // The cloud's parts, as the pieces' shared points join them: where their samples' rays
  // decide, every piece takes the rays' signs.
  ConnectedComponents<std::uint32_t> parts(n);
  for (const auto& [key, balance] : votes_) parts.join(std::uint32_t(key >> 32), std::uint32_t(key & 0xffffffffu));
  std::vector<std::int64_t> points(n, 0), voters(n, 0);
  for (std::uint32_t p = 0; p < n; ++p) {
    points[parts.find(p)] += rays_[p].points;
    voters[parts.find(p)] += rays_[p].voters;
  }
  PieceTurns out;
  out.seen.resize(n);
  for (std::uint32_t p = 0; p < n; ++p) out.seen[p] = rays_decide(voters[parts.find(p)], points[parts.find(p)]);
  // The strongest agreements first, then by the pieces' numbers: the same forest every run.
  std::vector<std::pair<std::uint64_t, std::int64_t>> votes;
  votes.reserve(votes_.size());
  for (const auto& [key, balance] : votes_)  // a pair's two pieces lie in one part: both take its signs, or neither
    votes.emplace_back(key, balance[out.seen[std::size_t(key >> 32)] ? 1 : 0]);
  std::sort(votes.begin(), votes.end(), [](const auto& x, const auto& y) {
    const std::int64_t sx = std::llabs(x.second), sy = std::llabs(y.second);
    return sx > sy || (sx == sy && x.first < y.first);
  });
  // Union-find with each piece's sign relative to its parent's.
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
  std::vector<char>& turn = out.flip;
  turn.resize(n);
  std::vector<FacingVote> facing(n);  // by each part's root in the forest
  std::vector<std::int64_t> seen(n, 0);  // the rays' votes, where the part takes their signs
  for (std::uint32_t p = 0; p < n; ++p) {
    const std::uint32_t r = find(p);
    turn[p] = char(against[p] ^ against[top[r]]);
    facing[r].add(out.seen[p] ? rays_[p].seen_facing : facing_[p], turn[p]);
    seen[r] += turn[p] ? -rays_[p].seen_sum : rays_[p].seen_sum;
  }
  // Each part (by its root) faces as its rays' votes sum, where they decide; else as its heights vote.
  std::vector<char> inward(n);
  for (std::uint32_t r = 0; r < n; ++r) inward[r] = out.seen[r] && seen[r] != 0 ? seen[r] < 0 : facing[r].sign() < 0;
  out.part.resize(n);
  for (std::uint32_t p = 0; p < n; ++p) {
    out.part[p] = find(p);
    turn[p] ^= inward[out.part[p]];
  }
  return out;
}

}  // namespace pss
