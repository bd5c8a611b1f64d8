// The parts of a cloud's mesh that no data hold (internal to src/mesh). Where a cloud is
// noisy, the MLS fits wrap a sample lying a few σ off the surface in a small closed bubble
// of its own: a 30,000-point sphere with noise 0.4 h meshed into 49 parts, a 10^6-point
// torus with noise 0.33 h into 290, each bubble around one or two samples.
#pragma once

#include <cstdint>

#include "pss/mesh/mesh_cloud.hpp"
#include "pss/mesh/triangle_mesh.hpp"
#include "pss/spatial/support_grid.hpp"

namespace pss::mesh_detail {

// Removes every part (vertices joined by triangles) whose bounding sphere, about its
// vertices' mean, holds fewer than kMinPartSamples of the grid's samples, and the vertices
// left unused. Returns the number of parts removed.
std::int64_t remove_unsupported_parts(TriangleMesh& mesh, const SupportGrid& samples);

}  // namespace pss::mesh_detail
