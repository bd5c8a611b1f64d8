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

// 1 when the key light is seen from `point` (n facing the viewer), 0 when not. A surface
// turned away from the light shades to zero key light anyway: no ray is needed. The ray
// leaves `offset` off the surface (the finder's secondary_offset of the hit).
template <class Finder>
PSS_HOST_DEVICE float key_light_visibility(const Finder& f, const TraceSettings& s, vec3 point, vec3 n, float offset,
                                           std::int32_t& rays) {
  if (glm::dot(n, s.shading.key_direction) <= 0) return 0.0f;
  ++rays;
  const Ray shadow_ray{point + offset * n, s.shading.key_direction};
  return f.secondary(shadow_ray, kInfinity).found() ? 0.0f : 1.0f;
}

template <class Finder>
PSS_HOST_DEVICE SecondaryHits trace_secondary(const Finder& f, const TraceSettings& s, const Ray& primary,
                                              const Hit& hit) {
  SecondaryHits out;
  if (!hit.found()) return out;
  const vec3 n = face_viewer(hit.normal, primary.dir);
  const float offset = f.secondary_offset(hit);
  if (s.shadows) out.shadow = key_light_visibility(f, s, hit.point, n, offset, out.rays);
  if (s.reflections) {
    const Ray bounce{hit.point + offset * n, reflect(primary.dir, n)};
    ++out.rays;
    out.reflection = f.secondary(bounce, kInfinity);
    if (out.reflection.found() && s.shadows) {
      const vec3 rn = face_viewer(out.reflection.normal, bounce.dir);
      out.reflection_shadow =
          key_light_visibility(f, s, out.reflection.point, rn, f.secondary_offset(out.reflection), out.rays);
    }
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
