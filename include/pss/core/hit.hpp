// What a surface finder reports for one ray, the one hit type of both finders (point clouds
// §5.2, volumes §5.1): the shared currency of the kernels, the shading, secondary rays and
// outputs.
#pragma once

#include <cstdint>

#include "pss/core/types.hpp"

namespace pss {

enum HitFlag : std::uint8_t {
  kHitFound = 1,      // the ray met the surface; the other fields are meaningful
  kHitConverged = 2,  // the last projection moved the point less than ε
  kHitCapped = 4,     // accepted because the iteration cap was reached (paper Table 2: 2 or 3)
  kHitRough = 8,      // a first approximation, never projected (paper's secondary rays)
  // The volume's --debug-projection (the paper's Figure 2): what the ray's first projection did.
  kHitPredictorMoved = 16,  // |P(r) − r| > ε
  kHitCorrectorMoved = 32,  // and |γ − P(r)| > ε
};

struct Hit {
  vec3 point{0.0f};
  float t = kInfinity;  // distance along the ray (unit direction)
  vec3 normal{0.0f};    // unit, as the surface defines it: not yet turned toward the viewer
  std::int32_t iterations = 0;  // projections spent on this ray, rejected candidates included
  std::uint32_t flags = 0;
  // The surface's length scale here over the finder's own (adaptive support: h_i/h of the
  // sample whose ball gave the hit); 1 where the scale is the same everywhere (volumes).
  float scale = 1;

  PSS_HOST_DEVICE bool found() const { return (flags & kHitFound) != 0; }
};

}  // namespace pss
