// The three kernels of a frame (render_frame.hpp), for any surface finder (trace.hpp): each
// pixel's primary ray, its secondary rays, its shading. Arrays are that backend's.
#pragma once

#include <cstdint>

#include "pss/core/hit.hpp"
#include "pss/render/camera.hpp"
#include "pss/render/trace.hpp"

namespace pss {

template <class Finder>
struct PrimaryRaysKernel {
  Finder finder;
  Camera camera;
  Hit* hits;
  PSS_HOST_DEVICE void operator()(std::int64_t i) const {
    hits[i] = finder.primary(camera.primary_ray(int(i % camera.width), int(i / camera.width)));
  }
};

template <class Finder>
struct SecondaryRaysKernel {
  Finder finder;
  Camera camera;
  TraceSettings settings;
  const Hit* hits;
  SecondaryHits* out;
  PSS_HOST_DEVICE void operator()(std::int64_t i) const {
    out[i] = trace_secondary(finder, settings, camera.primary_ray(int(i % camera.width), int(i / camera.width)), hits[i]);
  }
};

template <class Finder>
struct ShadePixelsKernel {
  Finder finder;
  Camera camera;
  TraceSettings settings;
  const Hit* hits;
  const SecondaryHits* secondary;  // null without secondary rays
  vec3* pixels;
  PSS_HOST_DEVICE void operator()(std::int64_t i) const {
    const SecondaryHits none;  // what a pixel without secondary rays sees
    pixels[i] = shade_pixel(finder, settings, camera.primary_ray(int(i % camera.width), int(i / camera.width)), hits[i],
                            secondary ? secondary[i] : none);
  }
};

}  // namespace pss
