// One rendered frame and the CPU driver that makes it from any surface finder (see
// trace.hpp): primary rays, secondary rays, shading, each a named phase of --stats. The
// CUDA driver (src/backend/cuda/render_frame.cuh) runs the same three kernels.
#pragma once

#include <cstdint>
#include <vector>

#include "pss/backend/cpu/parallel_for.hpp"
#include "pss/core/progress.hpp"
#include "pss/core/stats.hpp"
#include "pss/render/image.hpp"
#include "pss/render/trace.hpp"

namespace pss {

struct RenderedFrame {
  Camera camera;
  std::vector<Hit> hits;  // per pixel, row-major from the top row
  Image image;
  std::int64_t secondary_rays = 0;
};

template <class Finder>
RenderedFrame render_frame_cpu(const Finder& finder, const Camera& camera, const TraceSettings& settings, Stats& stats) {
  RenderedFrame frame;
  frame.camera = camera;
  const std::int64_t n = std::int64_t(camera.width) * camera.height;
  const auto ray_of = [&](std::int64_t i) { return camera.primary_ray(int(i % camera.width), int(i / camera.width)); };
  frame.hits.resize(static_cast<std::size_t>(n));
  {
    ScopedPhase phase(stats, "primary");
    Progress progress("primary rays", n);
    cpu::parallel_for(n, [&](std::int64_t i) { frame.hits[i] = finder.primary(ray_of(i)); }, &progress);
  }
  std::vector<SecondaryHits> secondary(static_cast<std::size_t>(n));
  if (settings.shadows || settings.reflections) {
    ScopedPhase phase(stats, "secondary");
    Progress progress("secondary rays", n);
    cpu::parallel_for(n, [&](std::int64_t i) {
      secondary[i] = trace_secondary(finder, settings, ray_of(i), frame.hits[i]);
    }, &progress);
  }
  for (const SecondaryHits& s : secondary) frame.secondary_rays += s.rays;
  {
    ScopedPhase phase(stats, "shading");
    frame.image = Image(camera.width, camera.height);
    cpu::parallel_for(n, [&](std::int64_t i) {
      frame.image.pixels[i] = shade_pixel(settings, ray_of(i), frame.hits[i], secondary[i]);
    });
  }
  return frame;
}

}  // namespace pss
