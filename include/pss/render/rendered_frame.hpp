// One rendered frame: per-pixel hits (or only their counts), the image and the count of
// secondary rays. The frame driver that makes it from any surface finder is
// render/render_frame.hpp.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/ext/vector_double3.hpp>

#include "pss/render/camera.hpp"
#include "pss/render/image.hpp"
#include "pss/render/trace.hpp"

namespace pss {

struct FrameSummary {
  std::int64_t rays = 0;  // primary rays, one per pixel
  std::int64_t hits = 0;
  std::int64_t secondary_rays = 0;
  std::int64_t converged = 0, capped = 0;
  double mean_iterations = 0;  // projections per primary ray that hit
  std::int64_t iterations = 0;  // projections of all primary rays, misses included

  // Counts one primary ray; mean_iterations is set by finish().
  void add(bool found, bool converged_hit, bool capped_hit, std::int64_t projections) {
    ++rays;
    iterations += projections;
    if (!found) return;
    ++hits;
    hit_iterations_ += projections;
    converged += converged_hit;
    capped += capped_hit;
  }
  void finish() { mean_iterations = hits ? double(hit_iterations_) / double(hits) : 0.0; }

 private:
  std::int64_t hit_iterations_ = 0;
};

// The counts of hits packed by hit_counts (frame_kernels.hpp), one a pixel: their projections
// up to 8191 each (secondary_rays is the frame's, which summarize() adds).
FrameSummary summary_of_counts(const std::vector<std::uint16_t>& counts);

// Which per-pixel hits come back with a frame: all of them (what --hits, an EXR's depth and
// normals and the viewer's screenshots read), or only their counts, for the frames a window
// just shows (a 1080p frame's hits are 83 MB to copy back from a GPU and lay out on the host,
// ten times its kernels' time: issue 29).
enum class FrameHits : unsigned char { all, summary };

struct RenderedFrame {
  Camera camera;
  std::vector<Hit> hits;  // per pixel, row-major from the top row; empty with FrameHits::summary
  FrameSummary summary;   // with FrameHits::summary, the primary hits' counts; read through summarize()
  Image image;
  std::int64_t secondary_rays = 0;
  glm::dvec3 origin{0.0};  // the world position of the frame's zero (a cloud's origin, cloud.hpp)
};

}  // namespace pss
