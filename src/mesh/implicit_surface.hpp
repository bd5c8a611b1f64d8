// What the meshes of clouds and of volumes share around march_tetrahedra: their implicit's
// kernels (implicit_kernels.hpp) run on a backend, batch by batch, with progress.
#pragma once

#include <algorithm>
#include <span>
#include <vector>

#include "pss/backend/mirror.hpp"
#include "pss/backend/parallel_for.hpp"
#include "pss/mesh/implicit_kernels.hpp"

namespace pss::mesh_detail {

// Regula falsi stops within this share of the cube's side of the surface, or after
// kRootSteps projections (implicit_kernels.hpp: about 2 on average).
inline constexpr float kRootTolerance = 1e-3f;
inline constexpr int kRootSteps = 8;

// Where the surface passes between two corners, the nearer lies within their distance of it
// (marching_tetrahedra.hpp: farther, the change of sign is a jump of the implicit).
inline constexpr float kMaxSlope = 1.0f;

template <class Kernel>
void run(Backend backend, const char* phase, std::int64_t n, const Kernel& kernel, Stats& stats) {
  Progress progress(phase, n);
  parallel_for(backend, phase, n, kernel, stats, &progress);
}

// The implicit's batches of corners and edges, each copied to `backend`, evaluated there
// and copied back; `implicit` holds that backend's views, which must outlive the result.
template <class Implicit>
ImplicitSurface implicit_surface(Backend backend, const Implicit& implicit, float cell, Stats& stats) {
  ImplicitSurface surface;
  surface.sample = [backend, implicit, &stats](std::span<const vec3> corners, std::span<CornerSample> samples,
                                               Progress& progress) {
    const Mirror<vec3> in(backend, corners);
    Mirror<CornerSample> result(backend, corners.size());
    parallel_for(backend, "mesh corners", std::int64_t(corners.size()),
                 SampleCornersKernel<Implicit>{implicit, in.data(), result.data()}, stats, &progress);
    const std::vector<CornerSample> taken = result.take();
    std::copy(taken.begin(), taken.end(), samples.begin());
  };
  surface.cross = [backend, implicit, cell, &stats](std::span<const EdgeCrossing> edges,
                                                      std::span<MeshVertex> vertices) {
    const Mirror<EdgeCrossing> in(backend, edges);
    Mirror<MeshVertex> result(backend, edges.size());
    run(backend, "mesh vertices", std::int64_t(edges.size()),
        CrossEdgesKernel<Implicit>{implicit, in.data(), result.data(), kRootTolerance * cell, kRootSteps}, stats);
    const std::vector<MeshVertex> taken = result.take();
    std::copy(taken.begin(), taken.end(), vertices.begin());
  };
  return surface;
}

}  // namespace pss::mesh_detail
