// The pinhole camera of both renderers, and the documented default view that frames an
// object so that images stay comparable over time:
// - the bounding sphere of the object's box (centre = box centre, radius = half the
//   diagonal) fills the smaller of the two fields of view exactly;
// - the eye orbits that centre: azimuth 0, elevation 0 puts it on +z looking along −z;
//   positive azimuth turns it toward +x, positive elevation raises it toward +y; y is up;
// - --fov is the vertical field of view in degrees.
// --look-at, --up, --distance, --zoom and --roll move the eye from there (CameraSettings);
// with another up u, azimuth 0 looks from +z's part across u (from −y's when u is near ±z).
#pragma once

#include <glm/ext/vector_double3.hpp>

#include "pss/core/types.hpp"

namespace pss {

struct CameraSettings {
  int width = 512;
  int height = 512;
  float azimuth_deg = 0;
  float elevation_deg = 0;  // in [−90, 90]
  float fov_deg = 35;       // vertical, in (0, 180)
  // Beyond the default view (each left at its default keeps it):
  bool has_look_at = false;
  glm::dvec3 look_at{0.0};  // the point orbited and looked at, instead of the box's centre (double:
                            // a world point far from zero, until a cloud's origin is taken off)
  vec3 up{0, 1, 0};      // the world's up: elevation is measured from the plane across it
  float distance = 0;    // of the eye from look_at (0: what frames the box at fov_deg)
  float zoom = 1;        // the distance divided by this
  float roll_deg = 0;    // the camera turned about the view direction, counter-clockwise as
                         // seen from behind it (the picture turns clockwise)
};

// The limits every caller's settings meet (validate): a frame keeps an image pixel and a hit
// record (about 64 bytes) per pixel, so 2^26 pixels (8192x8192) are about 4 GiB, and a side
// up to 16384 still allows wide panoramas.
inline constexpr int kMaxImageSide = 16384;
inline constexpr long long kMaxImagePixels = 1LL << 26;
// Doubles, as the CLI's flags are parsed: 1e-3f is above the decimal 0.001.
inline constexpr double kMinFovDeg = 1, kMaxFovDeg = 170;
inline constexpr double kMinZoom = 1e-3, kMaxZoom = 1e3;
inline constexpr double kMaxRollDeg = 360;

// Throws a one-line Error naming the first setting out of its range (a NaN is out of every
// range), or saying that the view looks along a non-default `up` (elevation ±90°), where
// the orbit's frame is undefined.
void validate(const CameraSettings& settings);

struct Camera {
  vec3 eye{0.0f};
  vec3 forward{0, 0, -1}, right{1, 0, 0}, up{0, 1, 0};  // orthonormal
  float tan_half_fov = 0.3f;                            // vertical
  int width = 1, height = 1;

  // The ray through the centre of pixel (px, py); row 0 is the top of the image.
  PSS_HOST_DEVICE Ray primary_ray(int px, int py) const {
    const float aspect = float(width) / float(height);
    const float x = (2.0f * (float(px) + 0.5f) / float(width) - 1.0f) * tan_half_fov * aspect;
    const float y = (1.0f - 2.0f * (float(py) + 0.5f) / float(height)) * tan_half_fov;
    return {eye, glm::normalize(forward + x * right + y * up)};
  }

  // The same view `factor` times smaller each way (rounded, at least one pixel): a viewer's
  // reduced-resolution frames while the camera moves.
  Camera reduced(int factor) const {
    Camera c = *this;
    c.width = (width + factor / 2) / factor > 1 ? (width + factor / 2) / factor : 1;
    c.height = (height + factor / 2) / factor > 1 ? (height + factor / 2) / factor : 1;
    return c;
  }

  // A degenerate box (one point, or all points equal) is framed as a unit sphere.
  static Camera framing(const Aabb& box, const CameraSettings& s);
};

}  // namespace pss
