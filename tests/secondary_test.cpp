// Secondary rays against analytic truth: a sphere's PSS hovering over a plane's, seen from
// above at an angle. Where the plane mirrors the sphere, where the sphere's shadow falls,
// and what the pixels there show follow from the two shapes in closed form.
//
// Tolerances: the PSS lies within ~1e-4 of the sphere (radius 0.5, h ≈ 0.07) and within ε of
// the plane (tests/render_test.cpp), so only rays whose analytic answer would change within
// kBand of the sphere's outline are left out; every other pixel must agree.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>

#include "pss/points/render_cloud.hpp"
#include "pss/render/trace.hpp"
#include "support/shapes.hpp"

namespace pss {
namespace {

const test::Sphere kSphere{vec3(0, 0, 1), 0.5f};
constexpr float kPlaneHalf = 1.5f;  // the plane's square [−1.5, 1.5]² at z = 0
constexpr float kBand = 0.02f;      // rays passing within this of the sphere's outline are not judged
const vec3 kUp(0, 0, 1);            // the plane's normal

// The sphere and plane of ShadowRays (render_test.cpp): about the same density on both.
PointCloud sphere_over_plane() {
  test::SampleOptions o;
  o.count = 3000;
  PointCloud cloud = test::sample(kSphere, o);
  o.count = 8600;
  const PointCloud plane = test::sample_plane(kPlaneHalf, o);
  cloud.positions.insert(cloud.positions.end(), plane.positions.begin(), plane.positions.end());
  return cloud;
}

// From the −y side, above, looking down at the plane in front of the sphere: the sphere's
// mirror image (centred at z = −1) shows in the plane around y ≈ −0.9.
Camera looking_down() {
  Camera c;
  c.eye = vec3(0, -3, 2.5f);
  c.forward = glm::normalize(vec3(0, -0.4f, 0.4f) - c.eye);
  c.right = glm::normalize(glm::cross(c.forward, kUp));
  c.up = glm::cross(c.right, c.forward);
  c.tan_half_fov = std::tan(0.35f);
  c.width = c.height = 64;
  return c;
}

// The key light from the upper left (−x) and the camera's side (−y): the sphere's shadow
// lies around (0.6, −0.5), whole on the plane and in view. Not along the fill light.
TraceSettings settings_for(const Camera& camera, bool shadows, bool reflections, float reflectivity = 0.5f) {
  TraceSettings s = TraceSettings::for_camera(camera, shadows, reflections, reflectivity);
  s.shading.key_direction = glm::normalize(vec3(-0.6f, 0.5f, 1.0f));
  // No highlights: at shininess 48 they turn the PSS's normal error (a degree or two on the
  // sphere) into colour errors of a few hundredths, the size of what the tests look for.
  s.shading.specular = 0;
  return s;
}

// The ray from o along unit d against the sphere: the distance of its line from the centre
// (`miss`, the sphere is hit when below the radius) and the first hit's t.
struct SphereCrossing {
  float miss = kInfinity;
  float t = kInfinity;
  bool hit() const { return miss < kSphere.radius; }
  bool near_outline() const { return std::abs(miss - kSphere.radius) < kBand; }
};
SphereCrossing cross_sphere(vec3 o, vec3 d) {
  SphereCrossing c;
  const vec3 to_centre = kSphere.center - o;
  const float along = glm::dot(to_centre, d);
  if (along <= 0 && glm::length(to_centre) > kSphere.radius) return c;  // it points away
  c.miss = glm::length(to_centre - along * d);
  if (c.hit()) c.t = along - std::sqrt(kSphere.radius * kSphere.radius - c.miss * c.miss);
  return c;
}

// A pixel whose primary ray meets the plane's square (3h inside its rim) before anything
// else, and the plane's analytic answers there.
struct PlanePixel {
  bool judged = false;  // on the plane, and no analytic answer within kBand of changing
  vec3 point{0.0f};     // where the ray meets z = 0
  vec3 mirrored{0.0f};  // the primary ray's direction reflected about z
  bool sees_sphere = false;   // the mirrored ray (from the code's start point) meets the sphere
  vec3 sphere_point{0.0f};    // and where
  bool shadowed = false;      // the ray toward the key light meets the sphere
};

PlanePixel plane_pixel(const Ray& ray, float rim, float offset, vec3 key) {
  PlanePixel p;
  if (ray.dir.z >= 0) return p;
  p.point = ray.at(-ray.origin.z / ray.dir.z);
  if (std::abs(p.point.x) > kPlaneHalf - rim || std::abs(p.point.y) > kPlaneHalf - rim) return p;
  const SphereCrossing primary = cross_sphere(ray.origin, ray.dir);
  if (primary.hit() || primary.near_outline()) return p;
  // Secondary rays start `offset` above the surface (RayPssParams::secondary_offset).
  const vec3 start = p.point + offset * kUp;
  p.mirrored = vec3(ray.dir.x, ray.dir.y, -ray.dir.z);
  const SphereCrossing mirror = cross_sphere(start, p.mirrored);
  const SphereCrossing shadow = cross_sphere(start, key);
  if (mirror.near_outline() || shadow.near_outline()) return p;
  p.sees_sphere = mirror.hit();
  if (p.sees_sphere) p.sphere_point = start + mirror.t * p.mirrored;
  p.shadowed = shadow.hit();
  p.judged = true;
  return p;
}

class SecondaryRays : public testing::Test {
 protected:
  static void SetUpTestSuite() {
    cloud_ = new PointCloud(sphere_over_plane());
    h_ = test::suggested_h(*cloud_);
    Stats stats;
    full_ = new PreparedCloud(*cloud_, params(SecondaryMode::full), Backend::cpu, stats);
  }
  static void TearDownTestSuite() {
    delete full_;
    delete cloud_;
  }
  static RayPssParams params(SecondaryMode mode) {
    RayPssParams p = RayPssParams::from_h(h_);
    p.secondary = mode;
    return p;
  }
  static PlanePixel pixel(const Camera& camera, int x, int y, const TraceSettings& s) {
    return plane_pixel(camera.primary_ray(x, y), 3 * h_, params(SecondaryMode::full).secondary_offset,
                       s.shading.key_direction);
  }

  static PointCloud* cloud_;
  static float h_;
  static PreparedCloud* full_;
};
PointCloud* SecondaryRays::cloud_ = nullptr;
float SecondaryRays::h_ = 0;
PreparedCloud* SecondaryRays::full_ = nullptr;

// Where the plane mirrors the sphere the reflection ray finds the sphere, at the point the
// mirrored ray meets it; elsewhere it finds nothing (it leaves the plane upward).
TEST_F(SecondaryRays, ReflectionsFindTheSphereWhereThePlaneMirrorsIt) {
  const Camera camera = looking_down();
  const TraceSettings settings = settings_for(camera, false, true);
  const PointFinder finder{full_->view()};
  int judged = 0, mirrors = 0, wrong = 0, off_point = 0;
  for (int y = 0; y < camera.height; ++y)
    for (int x = 0; x < camera.width; ++x) {
      const PlanePixel truth = pixel(camera, x, y, settings);
      if (!truth.judged) continue;
      ++judged;
      mirrors += truth.sees_sphere;
      const Ray ray = camera.primary_ray(x, y);
      const Hit hit = finder.primary(ray);
      ASSERT_TRUE(hit.found()) << x << ' ' << y;
      ASSERT_LT(glm::length(hit.point - truth.point), 1e-3f) << x << ' ' << y;
      const Hit r = trace_secondary(finder, settings, ray, hit).reflection;
      if (r.found() != truth.sees_sphere) {
        ++wrong;
        ADD_FAILURE() << "pixel " << x << ',' << y << (truth.sees_sphere ? " should" : " should not")
                      << " mirror the sphere; reflection hit at " << r.point.x << ' ' << r.point.y << ' '
                      << r.point.z;
        if (wrong > 5) return;
      } else if (r.found()) {
        // From the PSS's hit rather than the plane's point (ε apart), onto a sphere the PSS
        // follows to ~1e-4.
        off_point += glm::length(r.point - truth.sphere_point) > 2e-3f;
        EXPECT_LT(std::abs(kSphere.distance(r.point)), 1e-3f);
      }
    }
  EXPECT_GT(judged, 1500);
  EXPECT_GT(mirrors, 150);  // the mirror image covers ~300 pixels
  EXPECT_GT(judged - mirrors, 1000);
  EXPECT_EQ(wrong, 0);
  EXPECT_EQ(off_point, 0);
}

// With shadows and reflections, the mirrored sphere's points get their own shadow ray:
// those turned away from the key light (most of its underside, which the plane mirrors) are
// dark with no ray, those facing it see it (nothing lies above the sphere). Each pixel then
// traced one ray to the light from the plane, the bounce, and one from the sphere if lit.
TEST_F(SecondaryRays, ReflectedHitsTakeTheirOwnShadowRays) {
  const Camera camera = looking_down();
  const TraceSettings settings = settings_for(camera, true, true);
  const PointFinder finder{full_->view()};
  int judged = 0, dark = 0, lit = 0;
  for (int y = 0; y < camera.height; ++y)
    for (int x = 0; x < camera.width; ++x) {
      const PlanePixel truth = pixel(camera, x, y, settings);
      if (!truth.judged || !truth.sees_sphere || truth.shadowed) continue;
      const Ray ray = camera.primary_ray(x, y);
      const SecondaryHits sec = trace_secondary(finder, settings, ray, finder.primary(ray));
      ASSERT_TRUE(sec.reflection.found()) << x << ' ' << y;
      const float facing = glm::dot(kSphere.normal(sec.reflection.point), settings.shading.key_direction);
      if (std::abs(facing) < 0.05f) continue;  // the terminator: the PSS's normal decides
      ++judged;
      (facing > 0 ? lit : dark) += 1;
      EXPECT_EQ(sec.reflection_shadow, facing > 0 ? 1.0f : 0.0f) << x << ' ' << y;
      EXPECT_EQ(sec.rays, facing > 0 ? 3 : 2) << x << ' ' << y;
    }
  EXPECT_GT(dark, 50);
  EXPECT_GT(lit, 0);
}

// The shadow's outline on the plane: the key light is blocked exactly where the ray toward
// it meets the sphere.
TEST_F(SecondaryRays, ShadowOnThePlaneHasTheSpheresOutlineAlongTheKeyLight) {
  const Camera camera = looking_down();
  const TraceSettings settings = settings_for(camera, true, false);
  const PointFinder finder{full_->view()};
  int judged = 0, shadowed = 0, wrong = 0;
  for (int y = 0; y < camera.height; ++y)
    for (int x = 0; x < camera.width; ++x) {
      const PlanePixel truth = pixel(camera, x, y, settings);
      if (!truth.judged) continue;
      ++judged;
      shadowed += truth.shadowed;
      const Ray ray = camera.primary_ray(x, y);
      const SecondaryHits sec = trace_secondary(finder, settings, ray, finder.primary(ray));
      if ((sec.shadow == 0.0f) != truth.shadowed && ++wrong <= 5)
        ADD_FAILURE() << "pixel " << x << ',' << y << (truth.shadowed ? " should" : " should not")
                      << " be in the shadow; visibility " << sec.shadow;
    }
  EXPECT_GT(shadowed, 150);
  EXPECT_GT(judged - shadowed, 1000);
  EXPECT_EQ(wrong, 0);
}

// The colour shade_pixel must give a plane pixel, from the analytic plane, sphere, shadow
// and mirror image: the surface's own light, blended by Fresnel with what it mirrors.
vec3 expected_plane_colour(const TraceSettings& s, const Ray& ray, const PlanePixel& p) {
  const ShadingParams& sp = s.shading;
  // In the shadow the key light's Lambert term is missing (settings_for leaves no highlight).
  const vec3 lit = shade_surface(sp, sp.albedo, kUp, ray.dir, 1.0f);
  const vec3 key = sp.albedo * sp.key_color * std::max(0.0f, glm::dot(kUp, sp.key_direction));
  const vec3 local = s.shadows && p.shadowed ? lit - key : lit;
  if (!s.reflections) return local;
  // The sphere is convex and the plane lies below it: what of it the plane mirrors is lit
  // wherever it faces the key light.
  const vec3 sphere_n = face_viewer(kSphere.normal(p.sphere_point), p.mirrored);
  const vec3 mirrored = p.sees_sphere ? shade_surface(sp, sp.albedo, sphere_n, p.mirrored, 1.0f)
                                      : background(sp, p.mirrored);
  // Schlick's approximation, at the reflectivity asked for.
  const float k = sp.reflectivity + (1 - sp.reflectivity) * std::pow(1 + glm::dot(kUp, ray.dir), 5.0f);
  return local * (1.0f - k) + mirrored * k;
}

struct ColourCheck {
  int judged = 0, mirrors = 0, shadowed = 0, wrong = 0;
  double mirror_contrast = 0;  // mean |with the sphere − with the background| where it mirrors
};

// Every judged plane pixel of a rendered frame against expected_plane_colour, to within 0.015:
// twice the largest difference seen, the PSS's normal error on the sphere (a degree or two)
// as the mirror shows it.
ColourCheck check_plane_colours(const RenderedFrame& frame, const TraceSettings& s, float offset, float rim) {
  ColourCheck c;
  const Camera& camera = frame.camera;
  for (int y = 0; y < camera.height; ++y)
    for (int x = 0; x < camera.width; ++x) {
      const Ray ray = camera.primary_ray(x, y);
      const PlanePixel p = plane_pixel(ray, rim, offset, s.shading.key_direction);
      if (!p.judged) continue;
      ++c.judged;
      c.shadowed += p.shadowed;
      const vec3 expected = expected_plane_colour(s, ray, p);
      if (p.sees_sphere) {
        ++c.mirrors;
        PlanePixel without = p;
        without.sees_sphere = false;
        c.mirror_contrast += glm::length(expected - expected_plane_colour(s, ray, without));
      }
      const vec3 got = frame.image.at(x, y);
      if (glm::length(got - expected) > 0.015f && ++c.wrong <= 5)
        ADD_FAILURE() << "pixel " << x << ',' << y << (p.sees_sphere ? " (mirrors the sphere)" : "")
                      << (p.shadowed ? " (in the shadow)" : "") << ": " << got.x << ' ' << got.y << ' ' << got.z
                      << ", expected " << expected.x << ' ' << expected.y << ' ' << expected.z;
    }
  if (c.mirrors > 0) c.mirror_contrast /= c.mirrors;
  return c;
}

// The mirror image and the shadow show in the picture, blended as the shading says, and only
// when asked for.
TEST_F(SecondaryRays, RenderedPlaneShowsTheMirrorImageAndShadowOnlyWhenAskedFor) {
  const Camera camera = looking_down();
  const float offset = params(SecondaryMode::full).secondary_offset;
  for (const bool shadows : {false, true})
    for (const float reflectivity : {0.0f, ShadingParams{}.reflectivity, 0.5f}) {
      // Reflectivity 0 stands for reflections off.
      const bool reflections = reflectivity > 0;
      SCOPED_TRACE(std::string("shadows ") + (shadows ? "on" : "off") + ", reflectivity " +
                   std::to_string(reflectivity));
      const TraceSettings s = settings_for(camera, shadows, reflections, reflections ? reflectivity : 0.5f);
      ASSERT_EQ(s.shading.reflectivity, reflections ? reflectivity : 0.5f);
      Stats stats;
      const RenderedFrame frame = render_cloud(*full_, camera, s, Backend::cpu, stats);
      const ColourCheck c = check_plane_colours(frame, s, offset, 3 * h_);
      EXPECT_GT(c.judged, 1500);
      EXPECT_GT(c.mirrors, 150);
      EXPECT_GT(c.shadowed, 150);
      EXPECT_EQ(c.wrong, 0);
      // The mirror image stands out from the mirrored sky by far more than the tolerance.
      if (reflections) EXPECT_GT(c.mirror_contrast, reflectivity * 0.4);
    }
}

// --secondary: full projects reflection hits onto the PSS like primary hits; paper keeps the
// first local polynomial's hit, rough, off the sphere by the polynomial's error.
struct MirrorHits {
  int count = 0, rough = 0;
  double mean_distance = 0, max_distance = 0;
};
MirrorHits mirror_hits(const PointSurfaceView& view, const Camera& camera, const TraceSettings& s, float rim) {
  MirrorHits m;
  const PointFinder finder{view};
  for (int y = 0; y < camera.height; ++y)
    for (int x = 0; x < camera.width; ++x) {
      const Ray ray = camera.primary_ray(x, y);
      const PlanePixel p = plane_pixel(ray, rim, view.params.secondary_offset, s.shading.key_direction);
      if (!p.judged || !p.sees_sphere) continue;
      const Hit r = trace_secondary(finder, s, ray, finder.primary(ray)).reflection;
      if (!r.found()) continue;
      ++m.count;
      m.rough += (r.flags & kHitRough) != 0;
      const double d = std::abs(kSphere.distance(r.point));
      m.mean_distance += d;
      m.max_distance = std::max(m.max_distance, d);
    }
  if (m.count > 0) m.mean_distance /= m.count;
  return m;
}

TEST_F(SecondaryRays, SecondaryModeFullProjectsAndPaperStopsAtTheRoughHit) {
  const Camera camera = looking_down();
  const TraceSettings s = settings_for(camera, false, true);
  Stats stats;
  const PreparedCloud paper_cloud(*cloud_, params(SecondaryMode::paper), Backend::cpu, stats);
  const MirrorHits full = mirror_hits(full_->view(), camera, s, 3 * h_);
  const MirrorHits paper = mirror_hits(paper_cloud.view(), camera, s, 3 * h_);
  SCOPED_TRACE("full: " + std::to_string(full.count) + " hits, mean distance " + std::to_string(full.mean_distance) +
               "; paper: " + std::to_string(paper.count) + " hits, mean distance " +
               std::to_string(paper.mean_distance) + ", max " + std::to_string(paper.max_distance));
  // Both find the sphere wherever the plane mirrors it (~260 pixels).
  EXPECT_GT(full.count, 150);
  EXPECT_EQ(paper.count, full.count);
  // full: converged onto the PSS, which lies within ~1e-4 of the sphere.
  EXPECT_EQ(full.rough, 0);
  EXPECT_LT(full.mean_distance, 3e-4);
  EXPECT_LT(full.max_distance, 2e-3);
  // paper: every hit rough, several times farther off on average, still well within h.
  EXPECT_EQ(paper.rough, paper.count);
  EXPECT_GT(paper.mean_distance, 3 * full.mean_distance);
  EXPECT_LT(paper.max_distance, 0.1 * h_);
}

}  // namespace
}  // namespace pss
