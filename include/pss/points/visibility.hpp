// Which side of a sample is outside, as rays see it (issue 26: the orientation of a noisy
// scan, and of thin parts). A closed surface's outward normal leads out of it and its inward
// one into its other wall, whichever way the ray leans. So from each sample rays go along ±
// its normal and four directions tilted about it, through the samples' occupancy (each sample
// a disc in its tangent plane): where every ray on one side meets the surface and some on the
// other escape, the escaping side is out. Open ground says nothing (below it every ray
// escapes, above it most do), nor does a thin part's two faces (both sides escape) or a hollow
// between parts (some rays on both sides meet the surface). Unlike a spanning tree's signs,
// the rays see no neighbour: a thin part that noise has merged into one sheet, across which a
// tree turns every normal beyond it, does not mislead them (docs/paper-notes.md).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "pss/core/tree_signs.hpp"
#include "pss/core/types.hpp"

namespace pss {

class Progress;

// Pairs of opposite rays a sample casts: along its normal and four tilted kVisibilityTilt.
inline constexpr int kVisibilityPairs = 5;
inline constexpr float kVisibilityTilt = 0.5f;  // radians, about 29°
// The occupancy's voxels: the longest side of the samples' box in at most this many.
inline constexpr int kVisibilityCells = 256;

// A bitset of voxels over the samples' bounding box: those that the samples' discs pass
// through (radius r_i, at most 32 voxels, in the plane of normal n_i; a point whose normal
// has no direction, its own voxel).
class Occupancy {
 public:
  Occupancy(std::span<const vec3> points, std::span<const vec3> normals, std::span<const float> radius);
  // The voxels over `box` (the samples' finite points' box), none occupied yet: tile by tile,
  // each tile's samples are marked into the whole cloud's (tiles/orient_in_tiles.cpp).
  explicit Occupancy(const Aabb& box);
  // Marks these samples' discs.
  void mark(std::span<const vec3> points, std::span<const vec3> normals, std::span<const float> radius);
  // Whether the ray from `from` along the unit `direction` leaves the box through no occupied
  // voxel (a start outside the box has left it: the box is convex).
  bool escapes(vec3 from, vec3 direction) const;
  float cell() const { return cell_; }
  const Aabb& box() const { return box_; }
  // The bitset, 64 voxels a word, to carry it to another process and set it there (after
  // Occupancy(box) of the same box).
  std::span<const std::uint64_t> words() const { return bits_; }
  void set_words(std::vector<std::uint64_t>&& words);

 private:
  void mark(vec3 p, vec3 normal, float r);
  std::size_t bit(int x, int y, int z) const;  // a voxel's place in bits_
  bool occupied(int x, int y, int z) const;

  Aabb box_;
  vec3 lo_{0.0f};
  float cell_ = 1;
  int dims_[3] = {1, 1, 1};
  std::vector<std::uint64_t> bits_;
};

// A sample's disc in the occupancy, whose rays begin past it: half its support ρ_i, in core
// and tile by tile alike.
inline float visibility_radius(float rho) { return 0.5f * rho; }

// Per point: where every ray on the side opposite its normal meets the surface, how many of
// those on its normal's side escape; where every ray on its normal's side meets it, minus how
// many of the others escape; else 0. From −kVisibilityPairs to kVisibilityPairs: positive where
// the normal faces out. The rays begin 1.5 r_i from the point, past its own disc and its
// neighbours'; a point whose normal has no direction casts none. (A vote of each pair alone,
// escape(d) − escape(−d), read urban.las's valleys, whose rays up meet the slopes and whose
// rays down escape, as facing down: 45 % of its normals.)
// `progress`, where given, advances a step a point.
std::vector<std::int8_t> visibility_votes(std::span<const vec3> points, std::span<const vec3> normals,
                                          std::span<const float> radius, Progress* progress = nullptr);
// The same through a given occupancy (the whole cloud's, where a tile's samples vote).
std::vector<std::int8_t> visibility_votes(const Occupancy& occupancy, std::span<const vec3> points,
                                          std::span<const vec3> normals, std::span<const float> radius,
                                          Progress* progress = nullptr);

// Turns the normals (oriented along `tree`) where the rays say otherwise: in each part
// (`part_of`, numbered 0 to parts − 1) whose rays decide, the signs that agree best with the
// votes less kCutVotes for each of the tree's edges across which they change (exact, by
// dynamic programming over the tree), so that the parts a tree's turn across a merged thin
// part put inward face out again, and a part as a whole faces as the rays see it. A part
// decides where at least kDecidingShare of its points vote, and kDecidingVoters; elsewhere
// (open ground seen from above, where every ray escapes; a stray or a few, whose votes are
// chance) nothing turns. Returns per part whether it decided.
inline constexpr int kCutVotes = 64;
inline constexpr float kDecidingShare = 0.25f;
inline constexpr std::int64_t kDecidingVoters = 32;
inline constexpr bool rays_decide(std::int64_t voters, std::int64_t points) {
  return voters >= kDecidingVoters && double(voters) >= double(kDecidingShare) * double(points);
}
std::vector<char> face_as_seen(std::span<const vec3> points, std::span<vec3> normals, std::span<const float> radius,
                               std::span<const int> part_of, std::size_t parts, const SpanningTree& tree,
                               Progress* progress = nullptr);

}  // namespace pss
