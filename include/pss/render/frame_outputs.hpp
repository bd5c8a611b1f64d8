// What a renderer writes besides the image: --hits (the primary hits as a point cloud) and
// the frame's counts for --stats.
#pragma once

#include <cstdint>
#include <filesystem>

#include "pss/core/stats.hpp"
#include "pss/render/rendered_frame.hpp"

namespace pss {

struct FrameSummary {
  std::int64_t rays = 0;  // primary rays, one per pixel
  std::int64_t hits = 0;
  std::int64_t secondary_rays = 0;
  std::int64_t converged = 0, capped = 0;
  double mean_iterations = 0;  // projections per primary ray that hit
  std::int64_t iterations = 0;  // projections of all primary rays, misses included
};

FrameSummary summarize(const RenderedFrame& frame);

// Binary PLY: x y z nx ny nz (float) and px py (int) for every pixel whose primary ray hit.
// Normals face the camera.
void write_hits_ply(const std::filesystem::path& path, const RenderedFrame& frame);

// Adds rays, hits, secondary rays, mean iterations, image size and camera to stats.values().
void record_frame(Stats& stats, const RenderedFrame& frame);

}  // namespace pss
