// `pss render --color`: the samples' colours on the surface, against brute force and
// analytic expectations.
//
// Tolerances: the interpolated colour is a ratio of two float sums of ~60 terms of order 1,
// so its rounding is ~1e-6; 1e-4 leaves room for a sample at exactly ρ counted on one side
// only (its weight e^-4 ≈ 0.02 of the largest would move the mean by ~1e-3, far above it).
// A constant colour c interpolates to c to within that rounding, so its image equals the one
// shaded with albedo = c to 1e-5.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "pss/io/ply.hpp"
#include "pss/io/xyz.hpp"
#include "pss/points/render_cloud.hpp"
#include "support/cli.hpp"
#include "support/output_readers.hpp"
#include "support/shapes.hpp"

namespace pss {
namespace {

// Not pure primaries: 0 and 255 are the same in sRGB and linear light.
const Rgb8 kRed(230, 40, 20), kBlue(20, 60, 240);

// IEC 61966-2-1, written out here as the truth the library's table must match.
vec3 linear(Rgb8 c) {
  auto channel = [](int v) {
    const double s = v / 255.0;
    return float(s <= 0.04045 ? s / 12.92 : std::pow((s + 0.055) / 1.055, 2.4));
  };
  return vec3(channel(c.r), channel(c.g), channel(c.b));
}

// The unit sphere, red above y = 0 and blue below.
PointCloud two_colour_sphere() {
  test::SampleOptions o;
  o.count = 4000;
  PointCloud cloud = test::sample(test::Sphere{}, o);
  for (const vec3& p : cloud.positions) cloud.colors.push_back(p.y > 0 ? kRed : kBlue);
  return cloud;
}

RenderedFrame render(const PreparedCloud& prepared, const Camera& camera, const ShadingParams& shading,
                     bool secondary = false) {
  Stats stats;
  TraceSettings settings;
  settings.shading = shading;
  settings.shadows = secondary;
  settings.reflections = secondary;
  return render_cloud(prepared, camera, settings, Backend::cpu, stats);
}

CameraSettings view(int size, float elevation_deg) {
  CameraSettings s;
  s.width = s.height = size;
  s.elevation_deg = elevation_deg;
  return s;
}

TEST(Color, RedTopAndBlueBottomOfASphere) {
  const PointCloud cloud = two_colour_sphere();
  Stats stats;
  const PreparedCloud prepared(cloud, RayPssParams::from_h(test::suggested_h(cloud)), Backend::cpu, stats,
                               SurfaceColor::samples);
  const Camera camera = Camera::framing(cloud.bounds(), view(64, 0));
  ShadingParams shading = ShadingParams::for_camera(camera);
  shading.specular = 0;  // white highlights would add blue to the red half
  const RenderedFrame frame = render(prepared, camera, shading);
  int red = 0, blue = 0, hits = 0;
  for (std::size_t i = 0; i < frame.hits.size(); ++i) {
    const Hit& h = frame.hits[i];
    if (!h.found() || std::abs(h.point.y) < 0.3f) continue;  // away from the colours' border
    ++hits;
    const vec3 px = frame.image.pixels[i];
    red += h.point.y > 0 && px.r > 4 * px.b;
    blue += h.point.y < 0 && px.b > 4 * px.r;
  }
  EXPECT_GT(hits, 500);
  EXPECT_EQ(red + blue, hits);
}

// The weighted mean over every sample of the cloud, not through the grid.
vec3 brute_force_colour(const PointCloud& cloud, vec3 x, const ProjectionParams& p) {
  double sum[3] = {0, 0, 0}, weight_sum = 0;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const double d2 = glm::dot(cloud.positions[i] - x, cloud.positions[i] - x);
    if (d2 > double(p.rho) * p.rho) continue;
    const double w = std::exp(-d2 / (double(p.h) * p.h));
    const vec3 c = linear(cloud.colors[i]);
    for (int k = 0; k < 3; ++k) sum[k] += w * c[k];
    weight_sum += w;
  }
  return vec3(float(sum[0] / weight_sum), float(sum[1] / weight_sum), float(sum[2] / weight_sum));
}

TEST(Color, HitColourIsTheWeightedMeanOfTheSamplesWithinRho) {
  const PointCloud cloud = two_colour_sphere();
  const RayPssParams params = RayPssParams::from_h(test::suggested_h(cloud));
  Stats stats;
  const PreparedCloud prepared(cloud, params, Backend::cpu, stats, SurfaceColor::samples);
  const PointFinder finder{prepared.view()};
  const Camera camera = Camera::framing(cloud.bounds(), view(48, 10));
  int compared = 0, mixed = 0;
  for (int y = 0; y < camera.height; ++y) {
    for (int x = 0; x < camera.width; ++x) {
      const Hit hit = finder.primary(camera.primary_ray(x, y));
      if (!hit.found()) continue;
      const vec3 truth = brute_force_colour(cloud, hit.point, params.projection);
      const vec3 got = finder.albedo(hit, vec3(-1));
      for (int k = 0; k < 3; ++k) EXPECT_NEAR(got[k], truth[k], 1e-4) << x << ' ' << y << ' ' << k;
      ++compared;
      mixed += truth.r > 0.05f && truth.b > 0.05f;  // near y = 0, where the weights decide
    }
  }
  EXPECT_GT(compared, 400);
  EXPECT_GT(mixed, 20);
}

// A sphere over a plane, so that reflections meet the surface, in one colour: the image is
// the one shaded with that colour, decoded from sRGB, as the albedo.
TEST(Color, ConstantColourShadesAsThatAlbedoInLinearLight) {
  test::SampleOptions o;
  o.count = 3000;
  PointCloud cloud = test::sample(test::Sphere{vec3(0, 1, 0), 0.5f}, o);
  o.count = 8600;
  PointCloud plane = test::sample_plane(1.5f, o);
  for (vec3& p : plane.positions) p = vec3(p.x, 0.0f, p.y);  // the floor y = 0
  cloud.positions.insert(cloud.positions.end(), plane.positions.begin(), plane.positions.end());
  const Rgb8 colour(200, 120, 40);
  cloud.colors.assign(cloud.size(), colour);
  const RayPssParams params = RayPssParams::from_h(test::suggested_h(cloud));
  Stats stats;
  const PreparedCloud coloured(cloud, params, Backend::cpu, stats, SurfaceColor::samples);
  const PreparedCloud plain(cloud, params, Backend::cpu, stats);
  const Camera camera = Camera::framing(cloud.bounds(), view(64, 25));
  ShadingParams shading = ShadingParams::for_camera(camera);
  const RenderedFrame with_colour = render(coloured, camera, shading, true);
  shading.albedo = linear(colour);
  const RenderedFrame with_albedo = render(plain, camera, shading, true);
  int hits = 0, differ = 0;
  for (std::size_t i = 0; i < with_colour.hits.size(); ++i) {
    hits += with_colour.hits[i].found();
    const vec3 d = glm::abs(with_colour.image.pixels[i] - with_albedo.image.pixels[i]);
    differ += glm::max(d.x, glm::max(d.y, d.z)) > 1e-5f;
  }
  EXPECT_GT(hits, 500);
  EXPECT_EQ(differ, 0);
}

TEST(Color, PreparingColoursOfAColourlessCloudIsAnError) {
  test::SampleOptions o;
  o.count = 500;
  const PointCloud cloud = test::sample(test::Sphere{}, o);
  Stats stats;
  EXPECT_NE(test::error_of([&] {
              PreparedCloud(cloud, RayPssParams::from_h(0.2f), Backend::cpu, stats, SurfaceColor::samples);
            }).find("no per-point colours"),
            std::string::npos);
}

class ColorCli : public test::CliTest {};

TEST_F(ColorCli, RendersTheFilesColours) {
  write_ply(path("sphere.ply"), two_colour_sphere());
  const test::CliResult r =
      test::run_pss("render " + path("sphere.ply") + " --color --transparent --size 64x64 -o " + path("out.png"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const test::Image8 png = test::read_image8(path("out.png"));
  ASSERT_EQ(png.channels, 4);
  // The top and bottom thirds' hits (alpha 255); the specular highlight adds some blue to
  // the red, never as much.
  int top = 0, red = 0, bottom = 0, blue = 0;
  for (int y = 0; y < png.height; ++y) {
    for (int x = 0; x < png.width; ++x) {
      if (png.at(x, y, 3) == 0) continue;
      if (y < png.height / 3) {
        ++top;
        red += png.at(x, y, 0) > png.at(x, y, 2);
      } else if (y > 2 * png.height / 3) {
        ++bottom;
        blue += png.at(x, y, 2) > png.at(x, y, 0);
      }
    }
  }
  EXPECT_GT(top, 100);
  EXPECT_GT(bottom, 100);
  EXPECT_EQ(red, top);
  EXPECT_EQ(blue, bottom);
}

TEST_F(ColorCli, ColourlessFileIsAOneLineErrorAndWritesNothing) {
  test::SampleOptions o;
  o.count = 500;
  write_xyz(path("plain.xyz"), test::sample(test::Sphere{}, o));
  expect_clean_failure("render " + path("plain.xyz") + " --color -o " + path("out.png"),
                       "plain.xyz: has no per-point colours", path("out.png"));
}

}  // namespace
}  // namespace pss
