// The mesh of a volume's PSS (issue 27): iso and gradient surfaces of analytic volumes
// against their exact surfaces (a CT-like step, a distance ramp), their topology by Euler's
// formula, orientation towards lower values, every vertex a root of the implicit, a surface
// cut by the volume's box, the cell, and the refusals.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "pss/backend/backend.hpp"
#include "pss/core/error.hpp"
#include "pss/mesh/mesh_volume.hpp"
#include "pss/mesh/volume_implicit.hpp"
#include "support/cli.hpp"
#include "support/mesh_checks.hpp"
#include "support/render_truth.hpp"
#include "support/self_intersection.hpp"
#include "support/volumes.hpp"

namespace pss {
namespace {

PreparedVolume prepared(const Volume& volume, float iso, bool gradient = false, float h = 2) {
  VolumeSettings s;
  s.iso = iso;
  s.gradient = gradient;
  s.h = h;
  Stats stats;
  return prepare_volume(Volume(volume), s, stats);
}

VolumeMesh mesh_of(const PreparedVolume& volume, float cell = 0) {
  Stats stats;
  return mesh_volume(volume, cell, Backend::cpu, stats);
}

// A bright ball of radius R in air, its edge a smooth step about a voxel wide (as a CT's
// partial volume and blur make it): 100 inside, 0 outside, 50 exactly at distance R.
Volume ct_ball(vec3 center, float radius, float noise = 0, ivec3 dims = ivec3(40), float amplitude = 100) {
  test::SampleVolumeOptions o;
  o.dims = dims;
  o.noise = noise;
  return test::sample_volume(test::smooth_indicator(test::sphere_distance(center, radius), amplitude, 0.4f), o);
}

struct BallFit {
  double mean_distance = 0, max_distance = 0, mean_angle = 0, max_angle = 0;  // voxels; degrees
  bool normals_outward = true, triangles_outward = true;
  std::size_t inward_triangles = 0;
};

BallFit fit(const TriangleMesh& m, vec3 center, float radius) {
  BallFit f;
  for (std::size_t i = 0; i < m.positions.size(); ++i) {
    const vec3 d = m.positions[i] - center;
    const double distance = std::abs(double(glm::length(d)) - radius);
    f.mean_distance += distance / double(m.positions.size());
    f.max_distance = std::max(f.max_distance, distance);
    const float cosine = glm::dot(glm::normalize(d), m.normals[i]);
    f.normals_outward = f.normals_outward && cosine > 0.9f;
    const double angle = std::acos(std::min(1.0f, cosine)) * 180 / std::numbers::pi;
    f.mean_angle += angle / double(m.positions.size());
    f.max_angle = std::max(f.max_angle, angle);
  }
  for (const auto& t : m.triangles) {
    const vec3 a = m.positions[std::size_t(t[0])], b = m.positions[std::size_t(t[1])];
    const vec3 c = m.positions[std::size_t(t[2])];
    const bool outward = glm::dot(glm::cross(b - a, c - a), (a + b + c) / 3.0f - center) > 0;
    f.triangles_outward = f.triangles_outward && outward;
    f.inward_triangles += !outward;
  }
  return f;
}

TEST(VolumeMesh, ACtLikeBallIsOneWatertightOutwardSurfaceOnItsEdge) {
  const vec3 center(19.6f, 20.3f, 19.8f);
  const float radius = 12;
  for (const float noise : {0.0f, 3.0f}) {
    SCOPED_TRACE(noise);
    const VolumeMesh m = mesh_of(prepared(ct_ball(center, radius, noise), 50));
    test::expect_one_closed_surface(m.mesh, 2);
    EXPECT_EQ(test::crossing_triangle_pairs(m.mesh), 0);
    const double ball = 4.0 / 3.0 * std::numbers::pi * radius * radius * radius;
    EXPECT_NEAR(enclosed_volume(m.mesh), ball, 0.02 * ball);
    const BallFit f = fit(m.mesh, center, radius);
    EXPECT_LT(f.mean_distance, noise > 0 ? 0.06 : 0.04);
    EXPECT_LT(f.max_distance, noise > 0 ? 0.25 : 0.12);
    EXPECT_LT(f.mean_angle, noise > 0 ? 1.5 : 0.5);
    EXPECT_TRUE(f.normals_outward);
    EXPECT_TRUE(f.triangles_outward);
    EXPECT_FLOAT_EQ(m.cell, 1.0f);  // a voxel
    // A narrow band: about two corners evaluated per cube meshed, not the ball's inside.
    EXPECT_LT(m.counts.corners, 3 * m.counts.cubes_crossed);
    // The march's slivers merged into their neighbours (coarsen.hpp): about as many triangles
    // as marching cubes makes (Flying Edges: 3 per voxel² of area on bench/'s balls), where
    // the march alone makes 9, and few slivers.
    const double area = 4 * std::numbers::pi * radius * radius;
    EXPECT_LT(double(m.mesh.triangles.size()), 3.5 * area);
    EXPECT_GT(m.counts.collapsed_vertices, 0);
    std::size_t slivers = 0;
    for (const auto& t : m.mesh.triangles) slivers += test::triangle_quality(m.mesh, t) < 0.15;
    EXPECT_LT(double(slivers), 0.01 * double(m.mesh.triangles.size()));  // the march's: 5.6 %
  }
}

// A CT of thick slices: the ball sampled 6:1, its edge blurred over a third of a slice. The
// neighbourhoods, θ1 and the hit test measure lengths in the lattice's metric
// (VolumeView::metric), and the fits' planes are found there: with round balls in space
// (3u held one slice across the coarse axis) the mesh of (0.5, 0.5, 3) was open (220
// boundary edges) with normals 26° off on average, and that of (3, 3, 0.5) 6° off, 27° at
// worst, 0.3 from the sphere. Left: on (0.5, 0.5, 3) a few slivers (7 of 13,748, a thirtieth
// of the median area) fold inward where the surface grazes the thick slices.
TEST(VolumeMesh, AVolumeOfThickSlicesIsOneClosedSurfaceWithTheBallsNormals) {
  const vec3 center(16.2f, 15.8f, 17.3f);
  const float radius = 10;
  for (const auto& [spacing, dims] : {std::pair{vec3(0.5f, 0.5f, 3.0f), ivec3(64, 64, 12)},
                                      std::pair{vec3(3.0f, 3.0f, 0.5f), ivec3(12, 12, 70)}}) {
    SCOPED_TRACE(spacing.z);
    test::SampleVolumeOptions o;
    o.dims = dims;
    o.spacing = spacing;
    const Volume v = test::sample_volume(test::smooth_indicator(test::sphere_distance(center, radius), 100, 1.0f), o);
    const VolumeMesh m = mesh_of(prepared(v, 50));
    test::expect_one_closed_surface(m.mesh, 2);
    const BallFit f = fit(m.mesh, center, radius);
    EXPECT_LT(f.mean_distance, 0.2);  // world units; u = 0.91 and 1.65
    EXPECT_LT(f.max_distance, 0.6);
    EXPECT_LT(f.mean_angle, 4.5);
    EXPECT_LT(f.max_angle, 12);
    EXPECT_LE(f.inward_triangles, m.mesh.triangles.size() / 1000);
  }
}

// Every vertex is a root of the implicit on its edge: f at it is within the root's
// tolerance (10⁻³ cell), but where the surface passes within kEdgeMargin of a lattice corner
// and the vertex is kept that far inside its edge.
TEST(VolumeMesh, EveryVertexIsARootOfTheImplicit) {
  const PreparedVolume volume = prepared(ct_ball(vec3(20.2f, 19.7f, 20.1f), 11), 50);
  const VolumeMesh m = mesh_of(volume);
  const VolumeImplicit implicit{volume.scene(), m.cell};
  std::vector<float> residual;
  for (const vec3& p : m.mesh.positions) {
    const SignedDistance s = implicit(p);
    ASSERT_TRUE(s.valid);
    residual.push_back(std::abs(s.distance));
  }
  std::sort(residual.begin(), residual.end());
  EXPECT_LT(residual[residual.size() / 2], 1e-3f * m.cell);
  EXPECT_LT(residual[residual.size() * 99 / 100], (kEdgeMargin * std::sqrt(3.0f) + 1e-3f) * m.cell);
}

TEST(VolumeMesh, ATorusHasEulerCharacteristicZero) {
  test::SampleVolumeOptions o;
  o.dims = ivec3(44, 44, 24);
  o.scale = -40;
  o.offset = 100;
  const Volume v = test::sample_volume(test::torus_distance(vec3(21.7f, 21.4f, 11.6f), 13, 5), o);
  const VolumeMesh m = mesh_of(prepared(v, 100));
  test::expect_one_closed_surface(m.mesh, 0);
  const test::Field torus = test::torus_distance(vec3(21.7f, 21.4f, 11.6f), 13, 5);
  double worst = 0;
  for (const vec3& p : m.mesh.positions) worst = std::max(worst, double(torus.distance(p)));
  EXPECT_LT(worst, 0.1);
  EXPECT_GT(enclosed_volume(m.mesh), 0);
}

// A CT of a box with a bore (a logistic step of its signed distance, 0.04 to a voxel of
// 0.05): one watertight surface of genus one, on the faces away from the creases.
TEST(VolumeMesh, ABoxWithABoreIsOneClosedSurfaceOfGenusOne) {
  const test::BoredBox box;
  test::SampleVolumeOptions o;
  o.dims = ivec3(53);
  o.spacing = vec3(0.05f);
  o.origin = vec3(-1.31f, -1.29f, -1.3f);
  const test::Field field{[&](vec3 p) { return 100 / (1 + std::exp(box.distance(p) / 0.02f)); },
                          [&](vec3 p) { return -box.normal(p); }, 50};
  const VolumeMesh m = mesh_of(prepared(test::sample_volume(field, o), 50));
  test::expect_one_closed_surface(m.mesh, 0);
  EXPECT_GT(enclosed_volume(m.mesh), 0);
  float worst = 0;
  for (const vec3& p : m.mesh.positions)
    if (box.to_crease(p) > 0.2f) worst = std::max(worst, std::abs(box.distance(p)));
  EXPECT_LT(worst, 0.1f * 0.05f);  // a tenth of a voxel
}

// Half the ball lies beyond the box's face z = 0: its mesh ends there, open, on the ball.
TEST(VolumeMesh, ASurfaceCutByTheBoxStaysOpenAtTheBox) {
  const vec3 center(16.3f, 15.8f, 0.0f);
  const VolumeMesh m = mesh_of(prepared(ct_ball(center, 10, 0, ivec3(33, 33, 20)), 50));
  const MeshTopology shape = topology(m.mesh);
  EXPECT_TRUE(shape.manifold());
  EXPECT_EQ(shape.components, 1);
  EXPECT_GT(shape.boundary_edges, 0);
  EXPECT_EQ(shape.euler_characteristic(), 1);  // a disc
  for (const vec3& p : m.mesh.positions) {
    ASSERT_GE(p.z, -0.01f);
    ASSERT_NEAR(glm::length(p - center), 10.0f, 0.15f);
  }
}

// Inside the ball, 3 voxels below its surface, the values dip towards the iso-value without
// reaching it (to 54 of 100, iso 50; as in a tooth's dentine): the fit draws a sheet along
// the dip, which is no surface of the data. The corners that project onto it take the
// data's side, so the ball's surface beside it stays closed and the sheet is not meshed.
TEST(VolumeMesh, ADipThatNeverReachesTheIsoValueIsNoSurfaceNorAHole) {
  const vec3 center(19.6f, 20.3f, 19.8f);
  const float radius = 12;
  Volume v = ct_ball(center, radius);
  const VolumeView view = v.view();
  const float depth = 3, width = 0.8f;  // beyond the data test's reach, 0.75h = 1.5 voxels
  for (int k = 0; k < v.dims.z; ++k)
    for (int j = 0; j < v.dims.y; ++j)
      for (int i = 0; i < v.dims.x; ++i) {
        const float r = glm::length(view.position(i, j, k) - center) - (radius - depth);
        v.values[std::size_t(view.index(i, j, k))] -= 46 * std::exp(-r * r / (2 * width * width));
      }
  const VolumeMesh m = mesh_of(prepared(v, 50));
  test::expect_one_closed_surface(m.mesh, 2);
  EXPECT_LT(fit(m.mesh, center, radius).max_distance, 0.15);
  // Corners known only by their side do not grow the band: it stays narrow.
  EXPECT_LT(m.counts.corners, 3 * m.counts.cubes_crossed) << m.counts.cubes_crossed;
}

// A sharp step quantised to 8 bits saturates: inside, every voxel is 255 and the gradient 0,
// where no projection starts. At an iso-value near the top the surface still closes: such
// corners take the data's side.
TEST(VolumeMesh, ASaturatedInsideStillClosesTheSurface) {
  const vec3 center(19.6f, 20.3f, 19.8f);
  Volume v = ct_ball(center, 12, 0, ivec3(40), 300);
  for (float& x : v.values) x = std::round(std::min(x, 255.0f));
  const VolumeMesh m = mesh_of(prepared(v, 244));
  test::expect_one_closed_surface(m.mesh, 2);
}

// Voids a voxel wide a voxel inside the ball's surface (as in the bucky's shell; 36 of the
// voxels there set to 0): the PSS smooths them away where the data have small bubbles.
// Corners whose projection the data do not back take the data's side, and the sign change
// they make with their neighbours is meshed, not refused as a jump: the surface stays closed.
TEST(VolumeMesh, VoidsAVoxelWideLeaveNoHole) {
  const vec3 center(19.6f, 20.3f, 19.8f);
  Volume v = ct_ball(center, 12);
  const VolumeView view = v.view();
  int voids = 0;
  for (int k = 0; k < v.dims.z; ++k)
    for (int j = 0; j < v.dims.y; ++j)
      for (int i = 0; i < v.dims.x; ++i)
        if (std::abs(glm::length(view.position(i, j, k) - center) - 11) < 0.5f && (7 * i + 13 * j + 5 * k) % 37 == 0) {
          v.values[std::size_t(view.index(i, j, k))] = 0;
          ++voids;
        }
  ASSERT_GT(voids, 30);
  const VolumeMesh m = mesh_of(prepared(v, 50));
  EXPECT_TRUE(topology(m.mesh).watertight());
  EXPECT_EQ(m.counts.cubes_refused, 0);
}

// An iso-value within the noise of a plateau (the tooth's enamel at 230 of its 225–240):
// the ball's inside is 232 with noise of 3, so the data cross 230 at random all through
// it, in bubbles. Projections of neighbouring corners there land on different bubbles a
// side or two away, and their distances made the march take their change of sign for a
// jump (4 to 6 cubes refused, 16 to 24 boundary edges, on three seeds). Where the data put
// both corners on their sides, the data's surface passes between them; where a projection
// a side away contradicts the data, it went past the nearest sheet, and the data's side is
// taken: every part of the mesh is closed.
TEST(VolumeMesh, AnIsoValueWithinAPlateausNoiseMeshesClosed) {
  for (const std::uint32_t seed : {1u, 2u, 3u}) {
    SCOPED_TRACE(seed);
    test::SampleVolumeOptions o;
    o.dims = ivec3(40);
    o.noise = 3;
    o.seed = seed;
    const vec3 center(19.6f, 20.3f, 19.8f);
    const Volume v = test::sample_volume(test::smooth_indicator(test::sphere_distance(center, 12), 232, 0.4f), o);
    const VolumeMesh m = mesh_of(prepared(v, 230));
    EXPECT_EQ(m.counts.cubes_refused, 0);
    EXPECT_TRUE(topology(m.mesh).watertight()) << topology(m.mesh).boundary_edges << " boundary edges";
  }
}

// A corner's side is the data's exactly where the value there is on the side of the
// iso-value that f's sign says. Where the PSS smooths the plateau's bubbles away, f and the
// data disagree within a side of the PSS's sheet (there the change of sign may still be a
// jump); beyond, the corner takes the data's side. Where they agree, the projection stands
// however far it is (within the reach of two sides).
TEST(VolumeMesh, ACornersSideIsTheDatasWhereTheyAgree) {
  test::SampleVolumeOptions o;
  o.dims = ivec3(40);
  o.noise = 3;
  const Volume v = test::sample_volume(
      test::smooth_indicator(test::sphere_distance(vec3(19.6f, 20.3f, 19.8f), 12), 232, 0.4f), o);
  const PreparedVolume volume = prepared(v, 230);
  const VolumeImplicit implicit{volume.scene(), 1};
  int agree = 0, disagree = 0, agree_beyond_a_side = 0;
  for (int k = 4; k < 36; ++k)
    for (int j = 4; j < 36; ++j)
      for (int i = 4; i < 36; ++i) {
        const vec3 x{float(i), float(j), float(k)};
        const SignedDistance s = implicit(x);
        if (!s.valid) continue;
        const bool inside_by_data = v.values[std::size_t((k * 40 + j) * 40 + i)] > 230;
        const bool same = inside_by_data == (s.distance < 0);
        ASSERT_EQ(s.side_from_data, same) << i << " " << j << " " << k;
        ASSERT_TRUE(same || std::abs(s.distance) <= 1) << s.distance;
        if (s.on_surface) ++(same ? agree : disagree);
        agree_beyond_a_side += s.on_surface && same && std::abs(s.distance) > 1;
      }
  EXPECT_GT(disagree, 100);
  EXPECT_GT(agree_beyond_a_side, 100);
  EXPECT_GT(agree, 2 * disagree);
}

// The gradient surface of the same step is where |∇f| peaks: the sphere of radius R.
TEST(VolumeMesh, AGradientSurfaceIsTheStepsSteepestSheet) {
  const vec3 center(19.6f, 20.3f, 19.8f);
  const VolumeMesh m = mesh_of(prepared(ct_ball(center, 12), 0, true));
  const MeshTopology shape = topology(m.mesh);
  EXPECT_TRUE(shape.watertight());
  EXPECT_EQ(shape.euler_characteristic(), 2);
  const BallFit f = fit(m.mesh, center, 12);
  EXPECT_LT(f.mean_distance, 0.1);
  EXPECT_TRUE(f.normals_outward);
  EXPECT_TRUE(f.triangles_outward);
}

// Outward is towards lower values: a dark ball in bright surroundings faces its centre.
TEST(VolumeMesh, ADarkBallFacesItsBrighterSurroundings) {
  const vec3 center(19.6f, 20.3f, 19.8f);
  Volume v = ct_ball(center, 12);
  for (float& x : v.values) x = 100 - x;
  const VolumeMesh m = mesh_of(prepared(v, 50));
  EXPECT_LT(enclosed_volume(m.mesh), 0);
  for (std::size_t i = 0; i < m.mesh.positions.size(); ++i)
    ASSERT_LT(glm::dot(m.mesh.normals[i], m.mesh.positions[i] - center), 0);
}

// The cubes' side is the voxel u = (sx·sy·sz)^(1/3) by default, or the cell given; the
// triangles' edges scale with it, the surface stays where it is.
TEST(VolumeMesh, TheCellSetsTheTrianglesSize) {
  test::SampleVolumeOptions o;
  o.dims = ivec3(26, 22, 18);
  o.spacing = vec3(0.8f, 1.0f, 1.25f);
  const vec3 center(10.1f, 9.8f, 11.2f);
  const Volume v = test::sample_volume(test::smooth_indicator(test::sphere_distance(center, 6), 100, 0.8f), o);
  const PreparedVolume volume = prepared(v, 50);
  const VolumeMesh coarse = mesh_of(volume), fine = mesh_of(volume, 0.5f);
  EXPECT_NEAR(coarse.cell, 1.0f, 1e-6f);  // (0.8·1·1.25)^(1/3)
  EXPECT_FLOAT_EQ(fine.cell, 0.5f);
  const double ratio = double(fine.mesh.triangles.size()) / double(coarse.mesh.triangles.size());
  EXPECT_GT(ratio, 3.2);
  EXPECT_LT(ratio, 4.8);
  for (const VolumeMesh* m : {&coarse, &fine}) {
    EXPECT_TRUE(topology(m->mesh).watertight());
    EXPECT_LT(fit(m->mesh, center, 6).mean_distance, 0.1);
  }
}

TEST(VolumeMesh, TheMeshIsTheSameForAnyThreadCount) {
  const PreparedVolume volume = prepared(ct_ball(vec3(19.6f, 20.3f, 19.8f), 12, 3), 50);
  set_cpu_threads(1);
  const VolumeMesh one = mesh_of(volume);
  set_cpu_threads(2);
  const VolumeMesh two = mesh_of(volume);
  set_cpu_threads(0);
  EXPECT_EQ(one.mesh.triangles, two.mesh.triangles);
  ASSERT_EQ(one.mesh.positions.size(), two.mesh.positions.size());
  for (std::size_t i = 0; i < one.mesh.positions.size(); ++i) ASSERT_EQ(one.mesh.positions[i], two.mesh.positions[i]);
}

TEST(VolumeMesh, ACellTooFineOrNotANumberIsRefusedBeforeWork) {
  const PreparedVolume volume = prepared(ct_ball(vec3(19.6f, 20.3f, 19.8f), 12), 50);
  const std::string fine = test::error_of([&] { mesh_of(volume, 1e-3f); });
  EXPECT_NE(fine.find("too small for this volume"), std::string::npos) << fine;
  for (const float cell : {std::nanf(""), INFINITY, -1.0f}) {
    const std::string message = test::error_of([&] { mesh_of(volume, cell); });
    EXPECT_NE(message.find("the cell size must be a positive number"), std::string::npos) << message;
  }
}

}  // namespace
}  // namespace pss
