// The signs of normals oriented tile by tile (issue 28). Each tile orients its points and its
// halo's (orient_normals_in_parts): every connected part of that set from its highest point,
// turned to +z, as the whole cloud's orientation does. A part of the cloud that crosses tiles
// is then oriented in pieces, each with a sign of its own; where two pieces hold the same
// point (a tile's halo is its neighbour's own), their normals there vote on whether the two
// signs agree. The strongest votes first join the pieces into the cloud's parts (a spanning
// forest of the votes, as Prim's tree takes the cheapest edges first); each part keeps the
// sign of its piece grown from its highest point, and the others follow it. Then, as in core,
// the part faces the way its converged points vote: each piece's vote, over its tile's own
// points, added with the piece's sign (points/facing_vote.hpp).
#pragma once

#include <cstdint>
#include <unordered_map>
#include <vector>

#include "pss/points/facing_vote.hpp"

namespace pss {

class PieceSigns {
 public:
  // A new piece, grown from the point of height z and index `root` in the cloud, with the
  // facing vote of its tile's own points; its number.
  std::uint32_t add_piece(float z, std::uint64_t root, const FacingVote& vote);
  // Pieces a and b hold one point, with normals facing alike or not.
  void vote(std::uint32_t a, std::uint32_t b, bool alike);
  // Per piece, whether its normals turn.
  std::vector<char> turns() const;

 private:
  struct Root {
    float z;
    std::uint64_t index;
  };
  std::vector<Root> roots_;
  std::vector<FacingVote> facing_;
  std::unordered_map<std::uint64_t, std::int64_t> votes_;  // (a, b), a < b: alike minus not
};

}  // namespace pss
