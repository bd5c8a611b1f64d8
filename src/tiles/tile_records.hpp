// The records `pss project` keeps in scratch files between its steps tile by tile
// (tiles/project.hpp), written whole: every byte set, padding included.
#pragma once

#include <cstdint>

#include "pss/core/types.hpp"
#include "pss/io/tiled_cloud.hpp"
#include "pss/points/projection.hpp"
#include "pss/points/unit_frame.hpp"

namespace pss {

constexpr std::uint64_t kNoSample = std::uint64_t(-1);
constexpr std::uint32_t kNoPiece = std::uint32_t(-1);

// In a namespace of their own, where argument-dependent lookup finds std::swap alone (not
// core/platform.hpp's pss::swap, for kernels) when the records are sorted.
namespace records {

struct Projected {  // a point projected (or a sample's normal fitted), in its tile's bucket
  std::uint64_t index;
  std::uint64_t sample;  // the point its sample stands at (itself, unmerged), or kNoSample
  vec3 point, normal;  // unit frame
  float radius;        // ρ_i, unit frame: the orientation links the samples of each N(p_i)
  ProjectionStatus status;
  std::uint8_t unused[3] = {};
  // Whether the point stands for itself in the orientation: a sample's own point, or a point
  // of no sample (set aside), as in core (project_cloud.cpp).
  bool stands_for_itself() const { return sample == index || sample == kNoSample; }
};
static_assert(sizeof(Projected) == 48);

struct Oriented {  // a point oriented, in its window's bucket: its own tile's, or a halo's vote
  std::uint64_t index;
  vec3 point, normal;  // unit frame
  std::uint32_t piece;
  ProjectionStatus status;
  bool own;
  bool seen_turned = false;  // the rays' signs turn it in its piece (tiles/orient.hpp)
  std::uint8_t unused = 0;
};
static_assert(sizeof(Oriented) == 40);

}  // namespace records

using records::Oriented;
using records::Projected;

// The world halo that holds every sample within `unit_reach` of a tile's box: a little more
// for the rounding of the unit frame's floats (about 2^-25 of the box, whatever the reach).
inline double world_halo(double unit_reach, const UnitFrame& frame) {
  return (unit_reach + 0x1p-20) * frame.scale * (1 + 1e-5);
}

}  // namespace pss
