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
// The rays (points/visibility.hpp) give each tile's tree a second set of signs, those that
// agree best with them. Which set a piece takes is the cloud's part's to say, as in core: in
// a part where the rays decide (its pieces' own samples that vote, summed), every piece takes
// the rays' signs and the part faces as their votes sum; elsewhere the tree's, and the
// heights' vote.
#pragma once

#include <array>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "pss/points/facing_vote.hpp"

namespace pss {

// What the rays say of a piece, over its tile's own samples: how many there are and how many
// vote, their votes summed and the facing vote, both with the rays' signs (which the piece
// takes where they decide; where they do not, it faces as its heights vote).
struct PieceRays {
  std::int64_t points = 0, voters = 0;
  std::int64_t seen_sum = 0;
  FacingVote seen_facing;
};

// Per piece, whether its normals turn, whether they take the rays' signs first, and the part
// of the cloud it faces with (the pieces joined by their votes: numbered by one of them).
struct PieceTurns {
  std::vector<char> flip;
  std::vector<char> seen;
  std::vector<std::uint32_t> part;
  bool operator()(std::uint32_t piece, bool seen_turned) const {
    return (flip[piece] != 0) != (seen[piece] != 0 && seen_turned);
  }
};

class PieceSigns {
 public:
  // A new piece, grown from the point of height z and index `root` in the cloud, with the
  // facing vote of its tile's own points (the tree's signs) and the rays' say; its number.
  std::uint32_t add_piece(float z, std::uint64_t root, const FacingVote& vote, const PieceRays& rays = {});
  // Pieces a and b hold one point, with normals facing alike or not by their trees' signs;
  // a_seen, b_seen: the rays' signs turn it in a, in b.
  void vote(std::uint32_t a, std::uint32_t b, bool alike, bool a_seen = false, bool b_seen = false);
  PieceTurns turns() const;

 private:
  struct Root {
    float z;
    std::uint64_t index;
  };
  std::vector<Root> roots_;
  std::vector<FacingVote> facing_;
  std::vector<PieceRays> rays_;
  // (a, b), a < b: alike minus not, with the trees' signs and with the rays'.
  std::unordered_map<std::uint64_t, std::array<std::int64_t, 2>> votes_;
};

}  // namespace pss
