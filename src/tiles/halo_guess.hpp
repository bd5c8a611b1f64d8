// Where a tile's work doubles its halo from an eighth of the tile until the halo holds every
// answer its own points read (the spacing's estimate, the widths' passes): the tiles of one
// cloud need about the same halo, so each starts at the doublings most tiles before it
// needed (their median), not at an eighth again. Where the noise sets wide supports, tiles
// small beside them had each been worked on four or five times. The results are the same
// whatever the halo (the in-core ones to the last bit); only the work is less.
#pragma once

#include <array>
#include <cstdint>

namespace pss {

class HaloGuess {
 public:
  static constexpr float kFirstShare = 0.125f;  // of the tile's width

  // The halo to start a tile `width` wide with.
  float first(float width) const { return kFirstShare * width * float(std::uint64_t(1) << median()); }

  // A tile `width` wide held every answer with `halo`, a halo that first() and doublings gave.
  void held(float halo, float width) {
    int doublings = 0;
    while (doublings + 1 < int(count_.size()) && kFirstShare * width * float(std::uint64_t(1) << doublings) < halo)
      ++doublings;
    ++count_[std::size_t(doublings)];
    ++tiles_;
  }

 private:
  int median() const {
    std::uint64_t below = 0;
    for (std::size_t d = 0; d < count_.size(); ++d) {
      below += count_[d];
      if (2 * below > tiles_) return int(d);
    }
    return 0;
  }

  std::array<std::uint64_t, 40> count_{};
  std::uint64_t tiles_ = 0;
};

}  // namespace pss
