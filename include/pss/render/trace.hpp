// The per-pixel kernels every renderer shares, generic over its surface finder: secondary
// rays (one mirror bounce, ray depth 2 as in the paper, and shadow rays toward the key
// light) and the shading that composes a pixel from its hits.
//
// A Finder is a small struct passed by value (views of its arrays) with
//   Hit primary(const Ray&) const;                   // the surface along a camera ray
//   Hit secondary(const Ray&, float t_max) const;    // for reflection and shadow rays
//   float secondary_offset(const Hit&) const;        // how far off the surface they start
//   vec3 albedo(const Hit&, vec3 base) const;        // the surface's colour at a hit, or base
#pragma once

#include <cstdint>

#include "pss/core/hit.hpp"
#include "pss/render/shading.hpp"

namespace pss {

struct TraceSettings {
  ShadingParams shading;
  bool shadows = false;
  bool reflections = false;

  // The lights of `camera`'s view (ShadingParams::for_camera) with these secondary rays.
  static TraceSettings for_camera(const Camera& camera, bool shadows, bool reflections,
                                  float reflectivity = ShadingParams{}.reflectivity) {
    TraceSettings s;
    s.shading = ShadingParams::for_camera(camera);
    s.shading.reflectivity = reflectivity;
    s.shadows = shadows;
    s.reflections = reflections;
    return s;
  }
};

struct SecondaryHits {
  Hit reflection;
  float shadow = 1;             // of the primary hit
  float reflection_shadow = 1;  // of the reflection's hit
  std::int32_t rays = 0;        // secondary rays traced for this pixel
};

// A pixel's secondary rays, in order: the primary hit's shadow ray toward the key light, the
// mirror bounce, and the shadow ray of the bounce's hit. A surface turned away from the light
// shades to zero key light anyway: no ray is needed. Each ray leaves the finder's
// secondary_offset off its surface. The three go through one call of the finder in a loop
// that is not unrolled, so that a GPU kernel holds one copy of the finder's search and its
// stack one neighbourhood (tests/gpu/kernel_stacks.py), not three.
template <class Finder>
PSS_HOST_DEVICE SecondaryHits trace_secondary(const Finder& f, const TraceSettings& s, const Ray& primary,
                                              const Hit& hit) {
  SecondaryHits out;
  if (!hit.found()) return out;
  const vec3 key = s.shading.key_direction;
  const vec3 n = face_viewer(hit.normal, primary.dir);  // the side the secondary rays leave from
  const float offset = f.secondary_offset(hit);
  const Ray bounce{hit.point + offset * n, reflect(primary.dir, n)};
  PSS_NO_UNROLL
  for (int step = 0; step < 3; ++step) {
    Ray ray;
    if (step == 0) {  // the primary hit's shadow
      if (!s.shadows) continue;
      if (glm::dot(n, key) <= 0) {
        out.shadow = 0;
        continue;
      }
      ray = Ray{hit.point + offset * n, key};
    } else if (step == 1) {  // the mirror bounce
      if (!s.reflections) break;
      ray = bounce;
    } else {  // the bounce's shadow
      if (!s.shadows || !out.reflection.found()) break;
      const vec3 rn = face_viewer(out.reflection.normal, bounce.dir);
      if (glm::dot(rn, key) <= 0) {
        out.reflection_shadow = 0;
        break;
      }
      ray = Ray{out.reflection.point + f.secondary_offset(out.reflection) * rn, key};
    }
    ++out.rays;
    const Hit found = f.secondary(ray, kInfinity);
    if (step == 1)
      out.reflection = found;
    else
      (step == 0 ? out.shadow : out.reflection_shadow) = found.found() ? 0.0f : 1.0f;
  }
  return out;
}

template <class Finder>
PSS_HOST_DEVICE vec3 shade_pixel(const Finder& f, const TraceSettings& s, const Ray& primary, const Hit& hit,
                                 const SecondaryHits& sec) {
  const ShadingParams& p = s.shading;
  if (!hit.found()) return background(p, primary.dir);
  const vec3 n = face_viewer(hit.normal, primary.dir);
  const vec3 local = shade_surface(p, f.albedo(hit, p.albedo), n, primary.dir, sec.shadow);
  if (!s.reflections) return local;
  const vec3 dir = reflect(primary.dir, n);
  const vec3 reflected = sec.reflection.found()
                             ? shade_surface(p, f.albedo(sec.reflection, p.albedo),
                                             face_viewer(sec.reflection.normal, dir), dir, sec.reflection_shadow)
                             : background(p, dir);
  const float k = fresnel(p, n, primary.dir);
  return local * (1.0f - k) + reflected * k;
}

}  // namespace pss
