// The steps of the seams' turn (turn_flipped_normals.hpp), each over any of a grid's samples,
// so that tiles take them one tile at a time (src/tiles/seam_turn_in_tiles.cpp) and add up to the
// turn in core: the joins and the evidence are a sample's alone, with its neighbours in its
// support; the patches are numbered by their least sample in the cloud, not in a grid's
// order; the groups' and the stragglers' sums are kept in fixed point, the same in any order.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <unordered_map>
#include <vector>

#include "pss/core/types.hpp"
#include "pss/points/facing_vote.hpp"
#include "pss/spatial/support_grid.hpp"

namespace pss {

// A sample of no patch (a point that is no sample).
inline constexpr std::uint32_t kNoPatch = 0xffffffffu;
// Patches are weighed against each other only where they average this many samples or more.
inline constexpr std::size_t kFewestPerPatch = 8;

// The neighbours of sorted sample i (within ρ_i/2) that join its patch: their normals agree
// (n_i·n_j > 0.7) and they lie in each other's tangent plane. Seen from each sample of a
// pair in turn, so that the joins do not depend on which comes first in a grid.
void patch_joins(const SupportGridView& view, std::span<const vec3> normals, int i, std::vector<int>& joined);

// For turning one patch against another, and for keeping them as they are.
struct Evidence {
  std::int64_t flip = 0, keep = 0;
};
// Between patches a < b, keyed (a << 32) | b.
using PatchEvidence = std::unordered_map<std::uint64_t, Evidence>;

// What sorted sample i sees between its patch and its neighbours' (`patch` in sorted order).
void add_evidence(const SupportGridView& view, std::span<const vec3> normals, std::span<const std::uint32_t> patch,
                  int i, PatchEvidence& tally);
// `from` added to `into`.
void add_to(PatchEvidence& into, const PatchEvidence& from);

// add_evidence over any samples from any threads, each thread its own tally, summed after:
// sums, so the same for any thread count.
class EvidenceTallies {
 public:
  EvidenceTallies();
  void add(const SupportGridView& view, std::span<const vec3> normals, std::span<const std::uint32_t> patch, int i);
  PatchEvidence sum() const;

 private:
  std::vector<PatchEvidence> tallies_;  // a thread's each
};

// After the groups' turn, what sorted sample i of a straggling patch (fewer than
// kFewestPerPatch samples) says of its turn: the normals of its settled neighbours (`settled`,
// in sorted order) in whose tangent planes it lies, weighted as the fits weigh them, against
// its own; negative: turn.
double straggler_say(const SupportGridView& view, std::span<const vec3> normals, std::span<const char> settled, int i);

// The groups of patches that the evidence links, and which side of each turns. Each sample
// of the weighing groups is added (any order); then `turns` says per patch whether the groups'
// turn turns it.
class PatchGroups {
 public:
  PatchGroups(std::span<const std::uint64_t> patch_size, const PatchEvidence& between);
  bool linked() const { return linked_; }
  // A sample of `patch` at p (the unit frame) with its normal and 1/h_i².
  void add(std::uint32_t patch, vec3 p, vec3 normal, float inv_h2);
  std::vector<char> turns() const;

 private:
  // Sums in fixed point over a group's samples, each with its root patch's side kept.
  struct Sums {
    FacingVote vote;
    __int128 area = 0, outward = 0;
    __int128 normal[3] = {0, 0, 0}, position[3] = {0, 0, 0};
    __int128 facing[2][3] = {{0, 0, 0}, {0, 0, 0}};  // Σ n ρ² of the even and the odd side, as they are
    std::int64_t count[2] = {0, 0};
  };
  int enclosure_sign(const Sums& s) const;

  bool linked_ = false;
  std::vector<int> group_, side_;
  std::vector<Sums> sums_;     // per group that weighs (both its sides hold a patch that does)
  std::vector<int> weighing_;  // per group, its place in sums_, or −1
};

// The stragglers' says per patch, summed in fixed point.
class StragglerSays {
 public:
  explicit StragglerSays(std::size_t patches) : say_(patches, 0) {}
  void add(std::uint32_t patch, double say);
  std::vector<char> turns() const;

 private:
  std::vector<__int128> say_;
};

}  // namespace pss
