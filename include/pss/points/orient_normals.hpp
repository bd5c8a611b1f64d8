// Consistent orientation of unoriented normals (Hoppe et al. 1992): a minimum spanning tree
// over the neighbour graph with edge cost 1 − |nᵢ·nⱼ| propagates the sign along the
// smoothest paths; each connected part starts from its highest point, oriented to +z.
// The graph links p_i to every p_j within radius[j] of it: with the samples' supports ρ_j,
// the samples of p_i's own neighbourhood N(p_i), so that a sparse part, whose samples lie
// farther apart, stays connected. The parts the tree flipped, which show as seams, are then
// turned (turn_flipped_normals.hpp).
#pragma once

#include <span>

#include "pss/core/types.hpp"

namespace pss {

void orient_normals_consistently(std::span<const vec3> points, std::span<vec3> normals, std::span<const float> radius);

}  // namespace pss
