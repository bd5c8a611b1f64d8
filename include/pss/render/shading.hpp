// The default look shared by both renderers: a warm key light from the upper left of the
// viewer, a cool fill from the opposite side, a sky/ground hemisphere ambient, Blinn–Phong
// highlights, a vertical background gradient, and a Fresnel-weighted mirror reflection.
// Normals are turned toward the viewer first: PSS normals have no inside or outside.
#pragma once

#include "pss/render/camera.hpp"

namespace pss {

struct ShadingParams {
  vec3 key_direction{0, 0, 1};   // unit, from the surface toward the key light (world)
  vec3 fill_direction{0, 0, 1};  // unit, toward the fill light
  vec3 albedo{0.70f, 0.60f, 0.50f};
  vec3 key_color{0.95f, 0.88f, 0.78f};
  vec3 fill_color{0.22f, 0.26f, 0.34f};
  vec3 sky{0.34f, 0.42f, 0.55f};     // ambient from above, and the top of the background
  vec3 ground{0.16f, 0.14f, 0.13f};  // ambient from below, and the bottom of the background
  float ambient = 0.35f;             // scale of the hemisphere ambient
  float specular = 0.35f;
  float shininess = 48.0f;
  float reflectivity = 0.15f;  // Fresnel reflectance at normal incidence (Schlick)

  // The key light comes from the upper left, in front of the object, in camera space, so
  // every view is lit the same way.
  static ShadingParams for_camera(const Camera& camera) {
    ShadingParams p;
    p.key_direction = glm::normalize(-0.75f * camera.right + 0.6f * camera.up - 0.3f * camera.forward);
    p.fill_direction = glm::normalize(0.7f * camera.right - 0.2f * camera.up - 0.5f * camera.forward);
    return p;
  }
};

PSS_INLINE vec3 background(const ShadingParams& p, vec3 dir) {
  const float s = clamp(0.5f + 0.5f * dir.y, 0.0f, 1.0f);
  return p.ground + (p.sky - p.ground) * s;
}

// n or −n, whichever faces back along the ray that arrived along `ray_dir`.
PSS_INLINE vec3 face_viewer(vec3 n, vec3 ray_dir) { return glm::dot(n, ray_dir) > 0 ? -n : n; }

PSS_INLINE vec3 reflect(vec3 dir, vec3 n) { return dir - 2.0f * glm::dot(dir, n) * n; }

// Schlick's approximation of the Fresnel reflectance for the angle between n and −ray_dir.
PSS_INLINE float fresnel(const ShadingParams& p, vec3 n, vec3 ray_dir) {
  const float c = clamp(-glm::dot(n, ray_dir), 0.0f, 1.0f);
  const float m = 1.0f - c;
  return p.reflectivity + (1.0f - p.reflectivity) * (m * m) * (m * m) * m;
}

// The light leaving a surface point of diffuse colour `albedo` (p.albedo, or the finder's
// own) toward the viewer, without reflections. n faces the viewer; `shadow` is 1 where the
// key light is seen, 0 where it is blocked.
PSS_INLINE vec3 shade_surface(const ShadingParams& p, vec3 albedo, vec3 n, vec3 ray_dir, float shadow) {
  const float key = max(0.0f, glm::dot(n, p.key_direction)) * shadow;
  const float fill = max(0.0f, glm::dot(n, p.fill_direction));
  const float up = 0.5f + 0.5f * n.y;
  const vec3 ambient = p.ambient * (p.ground + (p.sky - p.ground) * up);
  const vec3 half = glm::normalize(p.key_direction - ray_dir);
  const float spec = key > 0 ? p.specular * pow(max(0.0f, glm::dot(n, half)), p.shininess) : 0.0f;
  return albedo * (ambient + key * p.key_color + fill * p.fill_color) + spec * shadow * p.key_color;
}

}  // namespace pss
