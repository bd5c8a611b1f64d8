// Vector types come from GLM, which compiles for host and device under nvcc
// (see docs/architecture.md: GLM_FORCE_CUDA must stay undefined).
#pragma once

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "pss/core/platform.hpp"

namespace pss {

using vec2 = glm::vec2;
using vec3 = glm::vec3;
using vec4 = glm::vec4;
using ivec3 = glm::ivec3;

PSS_INLINE float length2(vec3 v) { return glm::dot(v, v); }

PSS_INLINE bool is_finite(vec3 v) { return is_finite(v.x) && is_finite(v.y) && is_finite(v.z); }

// Whether a normal gives a direction: not zero, and finite.
PSS_INLINE bool has_direction(vec3 normal) {
  const float length = glm::length(normal);
  return length > 0 && is_finite(length);
}

// Ray with unit direction; points are origin + t * dir.
struct Ray {
  vec3 origin;
  vec3 dir;
  PSS_HOST_DEVICE vec3 at(float t) const { return origin + t * dir; }
};

struct Aabb {
  vec3 lo{kInfinity};
  vec3 hi{-kInfinity};
  PSS_HOST_DEVICE void grow(vec3 p) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  PSS_HOST_DEVICE void grow(const Aabb& b) {
    lo = glm::min(lo, b.lo);
    hi = glm::max(hi, b.hi);
  }
  PSS_HOST_DEVICE bool empty() const { return lo.x > hi.x; }
  PSS_HOST_DEVICE vec3 extent() const { return hi - lo; }
  PSS_HOST_DEVICE vec3 center() const { return 0.5f * (lo + hi); }
  PSS_HOST_DEVICE bool contains(vec3 p) const {
    return p.x >= lo.x && p.y >= lo.y && p.z >= lo.z && p.x <= hi.x && p.y <= hi.y && p.z <= hi.z;
  }
};

}  // namespace pss
