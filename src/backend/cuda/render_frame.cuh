// The render pipeline of render/rendered_frame.hpp on the GPU, for any surface finder whose views
// point to device memory: the same three kernels (primary, secondary, shading), each a
// named phase of --stats, then the hits and the image come back to the host.
#pragma once

#include "pss/backend/cuda/runtime.cuh"
#include "pss/render/rendered_frame.hpp"

namespace pss::cuda {

template <class Finder>
RenderedFrame render_frame_device(const Finder& finder, const Camera& camera, const TraceSettings& settings, Stats& stats) {
  RenderedFrame frame;
  frame.camera = camera;
  const std::int64_t n = std::int64_t(camera.width) * camera.height;
  DeviceBuffer<Hit> hits(static_cast<std::size_t>(n));
  DeviceBuffer<SecondaryHits> secondary(static_cast<std::size_t>(n));
  DeviceBuffer<vec3> pixels(static_cast<std::size_t>(n));
  Hit* h = hits.data();
  SecondaryHits* s = secondary.data();
  vec3* px = pixels.data();
  const Camera cam = camera;
  const TraceSettings ts = settings;
  {
    ScopedPhase phase(stats, "primary");
    parallel_for("primary", n, [=] __device__(std::int64_t i) {
      h[i] = finder.primary(cam.primary_ray(int(i % cam.width), int(i / cam.width)));
    });
  }
  {
    ScopedPhase phase(stats, "secondary");
    parallel_for("secondary", n, [=] __device__(std::int64_t i) {
      const Ray ray = cam.primary_ray(int(i % cam.width), int(i / cam.width));
      s[i] = ts.shadows || ts.reflections ? trace_secondary(finder, ts, ray, h[i]) : SecondaryHits{};
    });
  }
  {
    ScopedPhase phase(stats, "shading");
    parallel_for("shading", n, [=] __device__(std::int64_t i) {
      px[i] = shade_pixel(ts, cam.primary_ray(int(i % cam.width), int(i / cam.width)), h[i], s[i]);
    });
  }
  frame.hits = hits.to_host();
  const std::vector<SecondaryHits> sec = secondary.to_host();
  for (const SecondaryHits& x : sec) frame.secondary_rays += x.rays;
  frame.image = Image(camera.width, camera.height);
  pixels.download(frame.image.pixels);
  return frame;
}

}  // namespace pss::cuda
