// Consistent orientation of unoriented normals (Hoppe et al. 1992): a minimum spanning tree
// over the neighbour graph with edge cost 1 − |nᵢ·nⱼ|, plus how far p_j lies off p_i's
// tangent plane, propagates the sign along the smoothest paths on the surface; each
// connected part grows from its highest point, and then faces the way its converged points
// vote (facing_vote.hpp), the highest point's +z where they have no say. The graph links p_i to
// every p_j within radius[j] of it: with the samples' supports ρ_j, the samples of p_i's own
// neighbourhood N(p_i), so that a sparse part, whose samples lie farther apart, stays
// connected. The seams' turn that a file's normals go through (turn_flipped_normals.hpp)
// follows where the samples' estimated normals are oriented (sample_normals.hpp), not here:
// MLS's projections' normals and the tiles' go without it (docs/paper-notes.md).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "pss/core/tree_signs.hpp"
#include "pss/core/types.hpp"
#include "pss/points/projection.hpp"

namespace pss {

class SupportGrid;

// Throws Error unless there is one normal, one radius and one status (the projection's that
// gave the normal: which normals vote) per point.
void orient_normals_consistently(std::span<const vec3> points, std::span<vec3> normals, std::span<const float> radius,
                                 std::span<const ProjectionStatus> status);

// The same, for a caller that lends its arrays (pss project at 10^7 points, issue 28): the
// tree grows over the grid's sorted copies while the points and normals are freed; they come
// back as they were, the normals oriented. The radii are freed once indexed. Where it throws
// (an interrupt through Progress), the lent arrays may come back empty.
void orient_normals_consistently(std::vector<vec3>& points, std::vector<vec3>& normals, std::vector<float>&& radius,
                                 std::span<const ProjectionStatus> status);

// The same over the samples of a grid already built (sample_normals.hpp), in its sorted
// order: the supports it holds, κ·h_i, link the samples as the radii above do, and ties go
// by the cloud's order (original_index), without a second grid or a copy of the normals
// (issue 28: RIMLS's in-core peak at 10^6 points was the orientation's, 142 bytes a point).
void orient_grid_normals(const SupportGrid& grid, std::span<vec3> sorted_normals,
                         std::span<const ProjectionStatus> sorted_status);

// A file's normals of a grid's samples, in its sorted order (after the seams' turn,
// sample_normals.hpp), turned where the rays see them face in (visibility.hpp): oriented as
// estimated normals are (a tree over them, its signs turned where the rays see otherwise),
// then where a part so oriented holds a share of the file's facing against it but not nearly
// all (a flipped half whose seam noise hid from the turn), the file's turn to it; elsewhere
// (a file facing one way throughout, in or out), and in parts that the rays do not decide, the
// file keeps its signs. Returns how many turned.
std::size_t face_file_normals_as_seen(const SupportGrid& grid, std::span<vec3> sorted_normals);
// A part whose file's normals the rays see facing in for fewer than this share of its samples
// keeps them all: a file that faces out throughout lost 0.4–0.7 % of the dragon's normals to
// the rays' errors (0 to 1 spacing of noise; 12 % of its merged samples at 2), while a
// flipped half is half. So does a part whose file faces in for all but this share: a file
// facing one way throughout keeps that way (an inward one, a room's walls seen from inside).
inline constexpr double kFileAgainstShare = 0.15;

// The connected parts an orientation grew: each point's part, and each part's first point
// (its highest), by the points' indices; parts in the order they were grown.
struct OrientedParts {
  std::vector<int> of_point;
  std::vector<int> root;
};

// The same over a set of a cloud's points (a tile and its halo, issue 28), without a progress
// of its own and without the vote: ties go by id, each point's index in the cloud, so that
// the tree is the cloud's where the set holds it; each part faces as its highest point's +z.
// The parts say which signs the tiles must agree on, and whose votes add (tiles/orient.hpp).
// `tree`, where given, gets the tree's edges by the points' places (where the rays turn it).
OrientedParts orient_normals_in_parts(std::span<const vec3> points, std::span<vec3> normals,
                                      std::span<const float> radius, std::span<const std::uint64_t> id,
                                      SpanningTree* tree = nullptr);

}  // namespace pss
