// Orthonormal frame (u, v, n) at an origin: the local coordinate system on the plane
// H(n, q) in which the bivariate polynomial g(x, y) is fitted (paper §3).
#pragma once

#include "pss/core/types.hpp"

namespace pss {

struct Frame {
  vec3 origin;
  vec3 u, v, n;

  // Branchless basis from a unit normal (Duff et al., "Building an Orthonormal Basis,
  // Revisited", JCGT 2017): continuous except across n.z = 0 at one sign flip.
  PSS_HOST_DEVICE static Frame from_normal(vec3 origin, vec3 n) {
    const float sign = copysign(1.0f, n.z);
    const float a = -1.0f / (sign + n.z);
    const float b = n.x * n.y * a;
    Frame f;
    f.origin = origin;
    f.n = n;
    f.u = vec3(1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x);
    f.v = vec3(b, sign + n.y * n.y * a, -n.y);
    return f;
  }
  PSS_HOST_DEVICE vec3 to_local(vec3 p) const {
    const vec3 d = p - origin;
    return vec3(glm::dot(d, u), glm::dot(d, v), glm::dot(d, n));
  }
  PSS_HOST_DEVICE vec3 direction_to_local(vec3 d) const {
    return vec3(glm::dot(d, u), glm::dot(d, v), glm::dot(d, n));
  }
  PSS_HOST_DEVICE vec3 to_world(vec3 l) const { return origin + l.x * u + l.y * v + l.z * n; }
  PSS_HOST_DEVICE vec3 direction_to_world(vec3 l) const { return l.x * u + l.y * v + l.z * n; }
};

}  // namespace pss
