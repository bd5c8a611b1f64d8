// Coordinates relative to a cloud's bounding-box centre, in units of its largest extent:
// the float arithmetic of projection (squared distances, Gaussian weights) then sees
// numbers near 1 whatever the data's units, so a cloud at 1e30 or 1e-30 gives the same
// surface, up to the scale, as the same cloud at 1. Where a few points far from the rest
// make the box (BulkSample::box_of_strays: a stray at 10⁶ beside the bunny), the centre is
// the bulk's median instead: the box's, half-way to the stray, rounded the rest to the
// floats' steps there. The steps run tile by tile (src/tiles) take the whole cloud's frame
// (TiledCloud::unit_frame), so that they see the in-core floats.
#pragma once

#include <algorithm>
#include <cmath>
#include <span>
#include <utility>
#include <vector>

#include <glm/vec3.hpp>

#include "pss/core/bulk_sample.hpp"
#include "pss/core/types.hpp"

namespace pss {

struct UnitFrame {
  glm::dvec3 centre{0.0};
  double scale = 1;     // the box's largest extent; 1 when the points coincide
  double diagonal = 0;  // the box's diagonal, in the data's units

  vec3 to_unit(vec3 p) const { return vec3((glm::dvec3(p) - centre) / scale); }
  vec3 from_unit(vec3 p) const { return vec3(glm::dvec3(p) * scale + centre); }
};

// The frame about `centre` of a cloud whose box is [lo, hi].
inline UnitFrame unit_frame_about(glm::dvec3 lo, glm::dvec3 hi, glm::dvec3 centre) {
  UnitFrame f;
  const glm::dvec3 extent = hi - lo;
  f.centre = centre;
  const double largest = std::max({extent.x, extent.y, extent.z});
  f.scale = largest > 0 && std::isfinite(largest) ? largest : 1.0;
  f.diagonal = std::sqrt(extent.x * extent.x + extent.y * extent.y + extent.z * extent.z);
  return f;
}

// The centre of the unit frame of a cloud whose box is [lo, hi], from a sample of its
// positions (BulkSample): the box's, unless the box is the strays' (then the bulk's median).
inline glm::dvec3 frame_centre(std::vector<glm::dvec3> sample, glm::dvec3 lo, glm::dvec3 hi) {
  const BulkSample::Bulk bulk = BulkSample::bulk_of(std::move(sample));
  return BulkSample::box_of_strays(bulk, lo, hi) ? bulk.median : 0.5 * (lo + hi);
}

inline UnitFrame unit_frame(std::span<const vec3> points) {
  if (points.empty()) return {};
  glm::dvec3 lo(points[0]), hi(points[0]);
  BulkSample sample;
  for (const vec3& p : points) {
    lo = glm::min(lo, glm::dvec3(p));
    hi = glm::max(hi, glm::dvec3(p));
    sample.add(glm::dvec3(p));
  }
  return unit_frame_about(lo, hi, frame_centre(sample.kept(), lo, hi));
}

inline std::vector<vec3> to_unit(std::span<const vec3> points, const UnitFrame& f) {
  std::vector<vec3> out(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) out[i] = f.to_unit(points[i]);
  return out;
}

}  // namespace pss
