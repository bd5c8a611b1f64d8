// The frame driver of both backends, for any surface finder (see trace.hpp) whose views
// point to that backend's memory: primary rays, secondary rays, shading, each a kernel
// (frame_kernels.hpp) and a named phase of --stats; then the hits (or their counts) and the
// image on the host.
#pragma once

#include <cstdint>
#include <vector>

#include "pss/backend/mirror.hpp"
#include "pss/backend/parallel_for.hpp"
#include "pss/render/frame_kernels.hpp"
#include "pss/render/rendered_frame.hpp"

namespace pss {

template <class Finder>
RenderedFrame render_frame(Backend backend, const Finder& finder, const Camera& camera, const TraceSettings& settings,
                           Stats& stats, FrameHits keep = FrameHits::all) {
  const std::int64_t n = std::int64_t(camera.width) * camera.height;
  const bool traces_secondary = settings.shadows || settings.reflections;
  Mirror<Hit> hits(backend, std::size_t(n));
  // Without secondary rays nothing is written there, and nothing need come back.
  Mirror<SecondaryHits> secondary(backend, traces_secondary ? std::size_t(n) : 0);
  Mirror<std::uint8_t> secondary_rays(backend, traces_secondary ? std::size_t(n) : 0);
  Mirror<vec3> pixels(backend, std::size_t(n));
  {
    Progress progress("primary rays", n);
    parallel_for(backend, "primary", n, PrimaryRaysKernel<Finder>{finder, camera, hits.data()}, stats, &progress);
  }
  if (traces_secondary) {
    Progress progress("secondary rays", n);
    parallel_for(backend, "secondary", n,
                 SecondaryRaysKernel<Finder>{finder, camera, settings, hits.data(), secondary.data(),
                                             secondary_rays.data()},
                 stats, &progress);
  }
  parallel_for(backend, "shading", n,
               ShadePixelsKernel<Finder>{finder, camera, settings, hits.data(),
                                         traces_secondary ? secondary.data() : nullptr, pixels.data()},
               stats);

  RenderedFrame frame;
  frame.camera = camera;
  for (const std::uint8_t rays : secondary_rays.take()) frame.secondary_rays += rays;
  if (keep == FrameHits::all) {
    frame.hits = hits.take();
  } else {
    Mirror<std::uint16_t> counts(backend, std::size_t(n));
    parallel_for(backend, "hit counts", n, HitCountsKernel{hits.data(), counts.data()}, stats);
    frame.summary = summary_of_counts(counts.take());
  }
  frame.image.width = camera.width;
  frame.image.height = camera.height;
  frame.image.pixels = pixels.take();
  return frame;
}

}  // namespace pss
