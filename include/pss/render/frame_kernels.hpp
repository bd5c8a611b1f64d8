// The three kernels of a frame (render_frame.hpp), for any surface finder (trace.hpp): each
// pixel's primary ray, its secondary rays, its shading. Arrays are that backend's.
#pragma once

#include <cstdint>

#include "pss/core/hit.hpp"
#include "pss/render/camera.hpp"
#include "pss/render/trace.hpp"

namespace pss {

// The pixel of work item i in tiles of 8×4 pixels, band of four rows after band (narrower
// tiles at the right edge, shorter ones in the last band): a bijection of [0, width·height)
// that makes the 32 rays of a GPU warp one compact tile rather than a row of 32. A finder
// whose kTiledRays is true has its rays run in this order: on an H200 it took the engine's
// frames 26.4 → 20.5 ms (active threads per warp 3.4 → 4.7), but the bunny's 5.8 → 7.0 ms,
// so point clouds keep the rows (docs/benchmarks.md, issue 29).
PSS_INLINE std::int64_t tiled_pixel(std::int64_t i, int width, int height) {
  constexpr int kTileWidth = 8, kTileHeight = 4;
  const std::int64_t band = i / (std::int64_t(width) * kTileHeight);
  const int rows = min(kTileHeight, int(height - band * kTileHeight));
  const std::int64_t j = i - band * width * kTileHeight;
  const int column = int(j / (kTileWidth * rows));
  const int x0 = column * kTileWidth, columns = min(kTileWidth, width - x0);
  const int k = int(j - std::int64_t(column) * kTileWidth * rows);
  return (band * kTileHeight + k / columns) * width + x0 + k % columns;
}

// The pixel of work item i for a finder's rays: tiled or row by row (kTiledRays).
template <class Finder>
PSS_INLINE std::int64_t ray_pixel(std::int64_t i, const Camera& camera) {
  return Finder::kTiledRays ? tiled_pixel(i, camera.width, camera.height) : i;
}

template <class Finder>
struct PrimaryRaysKernel {
  Finder finder;
  Camera camera;
  Hit* hits;
  PSS_HOST_DEVICE void operator()(std::int64_t i) const {
    const std::int64_t p = ray_pixel<Finder>(i, camera);
    hits[p] = finder.primary(camera.primary_ray(int(p % camera.width), int(p / camera.width)));
  }
};

template <class Finder>
struct SecondaryRaysKernel {
  Finder finder;
  Camera camera;
  TraceSettings settings;
  const Hit* hits;
  SecondaryHits* out;
  std::uint8_t* rays;  // out[p].rays again: what the host reads back to count them (1 byte, not out's 56)
  PSS_HOST_DEVICE void operator()(std::int64_t i) const {
    const std::int64_t p = ray_pixel<Finder>(i, camera);
    out[p] = trace_secondary(finder, settings, camera.primary_ray(int(p % camera.width), int(p / camera.width)), hits[p]);
    rays[p] = std::uint8_t(out[p].rays);
  }
};

// A primary hit in 16 bits, for the frames whose hits stay where they were made
// (FrameHits::summary): found, converged, capped, and its projections (up to 8191).
PSS_INLINE std::uint16_t hit_counts(const Hit& h) {
  const int iterations = h.iterations < 8191 ? h.iterations : 8191;
  return std::uint16_t((h.found() ? 1 : 0) | (h.flags & kHitConverged ? 2 : 0) | (h.flags & kHitCapped ? 4 : 0) |
                       (iterations << 3));
}

struct HitCountsKernel {
  const Hit* hits;
  std::uint16_t* counts;
  PSS_HOST_DEVICE void operator()(std::int64_t i) const { counts[i] = hit_counts(hits[i]); }
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
