// The mesh of a PSS (issue 27): marching tetrahedra on analytic implicits (topology by
// Euler's formula, vertices on the zero set), the topology checks themselves on meshes made
// by hand, and the mesh of sampled shapes against their analytic surfaces.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "pss/backend/cpu/parallel_for.hpp"
#include "pss/core/memory.hpp"
#include "pss/io/point_cloud_file.hpp"
#include "pss/mesh/marching_tetrahedra.hpp"
#include "pss/mesh/mesh_cloud.hpp"
#include "pss/mesh/cloud_implicit.hpp"
#include "support/analytic_implicit.hpp"
#include "support/cli.hpp"
#include "support/mesh_checks.hpp"
#include "support/render_truth.hpp"
#include "support/self_intersection.hpp"
#include "support/shapes.hpp"

namespace pss {
namespace {

using test::analytic;
using test::march;

// The triangle's normal by its winding, unit.
vec3 face_normal(const TriangleMesh& m, const std::array<int, 3>& t) {
  const vec3 a = m.positions[std::size_t(t[0])];
  return glm::normalize(glm::cross(m.positions[std::size_t(t[1])] - a, m.positions[std::size_t(t[2])] - a));
}

// A unit sphere off the lattice's symmetry, marched in cubes of 0.1.
const test::Sphere kSphere{vec3(0.013f, -0.021f, 0.007f), 1.0f};
TriangleMesh marched_sphere(MarchCounts& counts) {
  const ImplicitSurface s =
      analytic([&](vec3 p) { return kSphere.distance(p); }, [&](vec3 p) { return kSphere.normal(p); });
  const vec3 seed[] = {kSphere.center + vec3(1, 0, 0)};
  return march(s, vec3(-1), vec3(1), 0.1f, seed, counts);
}

TEST(MarchingTetrahedra, ASphereIsOneWatertightOutwardSurface) {
  const test::Sphere& sphere = kSphere;
  MarchCounts counts;
  const TriangleMesh m = marched_sphere(counts);
  const MeshTopology t = topology(m);
  EXPECT_TRUE(t.watertight());
  EXPECT_EQ(t.euler_characteristic(), 2);
  EXPECT_EQ(t.components, 1);
  EXPECT_EQ(t.unreferenced_vertices, 0);
  // Only the band: the cubes the surface crosses and their neighbours, not the box's 22³.
  EXPECT_LT(counts.cubes_visited, 3 * counts.cubes_crossed);
  for (std::size_t i = 0; i < m.positions.size(); ++i) {
    EXPECT_NEAR(sphere.distance(m.positions[i]), 0.0f, 1e-5f);
    EXPECT_GT(glm::dot(m.normals[i], sphere.normal(m.positions[i])), 0.9999f);
  }
  for (const auto& tri : m.triangles)
    EXPECT_GT(glm::dot(face_normal(m, tri), sphere.normal(m.positions[std::size_t(tri[0])])), 0.5f);
  // It encloses the ball's volume (to the chords' loss), and so it does with a small hole.
  const double ball = 4.0 / 3.0 * 3.14159265358979;
  EXPECT_NEAR(enclosed_volume(m), ball, 0.02 * ball);
  TriangleMesh holed = m;
  holed.triangles.pop_back();
  EXPECT_NEAR(enclosed_volume(holed), ball, 0.02 * ball);
}

// Which way the normal at P(x) faces: the nearest sample's whose normal lies along ±n says,
// not a nearer one across a crease (its normal nearly perpendicular to n); where none lies
// along n (a thin part's fold), the nearest of all.
TEST(CloudImplicit, TheOutsideIsTheNearestSampleAlongTheNormalElseTheNearest) {
  const std::vector<vec3> points = {vec3(0.0f), vec3(0.1f, 0.0f, 0.0f)};
  const std::vector<vec3> normals = {vec3(-1, 0, 0), vec3(0, 0, 1)};
  const std::vector<float> h(2, 1.0f);
  SupportGrid grid(points, h, 2.0f);
  std::vector<vec3> sorted(2);
  for (std::size_t i = 0; i < 2; ++i) sorted[i] = normals[std::size_t(grid.original_index()[i])];
  grid.set_normals(sorted);
  const SupportGridView view = grid.view();
  const vec3 x(0.1f, 0.0f, 0.0f);  // on the second sample
  EXPECT_EQ(normal_along(view, x, vec3(0, 0, -1)), vec3(0, 0, 1));
  EXPECT_EQ(normal_along(view, x, vec3(1, 0, 0)), vec3(-1, 0, 0));      // the nearer lies across
  EXPECT_EQ(normal_along(view, x, glm::normalize(vec3(1, 0, 3))), vec3(0, 0, 1));
  EXPECT_EQ(normal_along(view, x, vec3(0, 1, 0)), vec3(0, 0, 1));       // none along: the nearest
  EXPECT_EQ(normal_along(view, vec3(9.0f), vec3(0, 1, 0)), vec3(0.0f));  // none holds x
}

// A surface with holes counts closed by its holes' lids while they are small beside it, as
// the dragon's scan (a 1/58 of its edges on holes): the sign of its volume says which way
// it faces. Wider openings enclose nothing.
TEST(EnclosedVolume, HolesCountClosedByTheirLidsOpeningsCountNothing) {
  const test::Sphere& sphere = kSphere;
  MarchCounts counts;
  const TriangleMesh m = marched_sphere(counts);
  const double ball = 4.0 / 3.0 * 3.14159265358979;
  // Without its triangles above a height: caps of 10 % and 20 % of its area, and half.
  auto cut = [&](float above) {
    TriangleMesh c = m;
    c.triangles.clear();
    for (const auto& t : m.triangles)
      if (m.positions[std::size_t(t[0])].z - sphere.center.z < above) c.triangles.push_back(t);
    return c;
  };
  // The lids are flat: the ball less its caps of height c, π c² (3 − c)/3.
  auto less_caps = [&](double c, int caps) { return ball - caps * 3.14159265358979 * c * c * (3 - c) / 3; };
  TriangleMesh capped = cut(0.8f), wide = cut(0.6f);
  EXPECT_NEAR(enclosed_volume(capped), less_caps(0.2, 1), 0.02 * ball);
  EXPECT_NEAR(enclosed_volume(wide), less_caps(0.4, 1), 0.02 * ball);
  turn_inside_out(capped);
  EXPECT_NEAR(enclosed_volume(capped), -less_caps(0.2, 1), 0.02 * ball);
  EXPECT_EQ(enclosed_volume(cut(0.0f)), 0.0);  // a hemisphere: its lid is half its area
  EXPECT_EQ(enclosed_volume(cut(-0.2f)), 0.0);
  // Two holes far apart, each with its own lid: the caps at both poles.
  TriangleMesh two = m;
  two.triangles.clear();
  for (const auto& t : m.triangles)
    if (std::abs(m.positions[std::size_t(t[0])].z - sphere.center.z) < 0.8f) two.triangles.push_back(t);
  EXPECT_NEAR(enclosed_volume(two), less_caps(0.2, 2), 0.02 * ball);
  // The share of the area in parts counted closed: a cap's height c takes 2π c of the 4π.
  double share = -1;
  enclosed_volume(capped, &share);
  EXPECT_EQ(share, 1.0);
  enclosed_volume(cut(0.0f), &share);
  EXPECT_EQ(share, 0.0);
  TriangleMesh both = cut(0.6f);  // less a cap of 0.4: 0.8 of the sphere's area, closed
  const TriangleMesh open = cut(0.0f);  // a hemisphere, open, beside it
  const int offset = int(both.positions.size());
  for (const vec3& p : open.positions) both.positions.push_back(p + vec3(5, 0, 0));
  for (auto t : open.triangles) both.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
  enclosed_volume(both, &share);
  EXPECT_NEAR(share, 0.8 / (0.8 + 0.5), 0.02);
}

TEST(MarchingTetrahedra, ATorusHasEulerCharacteristicZero) {
  const test::Torus torus{1.0f, 0.35f};
  const ImplicitSurface s = analytic([&](vec3 p) { return torus.distance(p); }, [&](vec3 p) { return torus.normal(p); });
  const vec3 seed[] = {vec3(1.35f, 0, 0)};  // one seed: the band follows the surface round
  MarchCounts counts;
  const TriangleMesh m = march(s, vec3(-1.4f, -1.4f, -0.4f), vec3(1.4f, 1.4f, 0.4f), 0.07f, seed, counts);
  const MeshTopology t = topology(m);
  EXPECT_TRUE(t.watertight());
  EXPECT_EQ(t.euler_characteristic(), 0);
  EXPECT_EQ(t.components, 1);
  for (const vec3& p : m.positions) EXPECT_NEAR(torus.distance(p), 0.0f, 1e-5f);
  // Its inner side turns 34° across a cube and its neighbours, but it has no crease: no
  // tangent planes meet on it.
  EXPECT_EQ(counts.crease_vertices, 0);
}

// Where the implicit cannot be trusted the mesh ends: an open, manifold surface.
TEST(MarchingTetrahedra, TheMeshEndsWhereTheImplicitIsInvalid) {
  const test::Sphere sphere;
  const ImplicitSurface s = analytic([&](vec3 p) { return sphere.distance(p); }, [&](vec3 p) { return sphere.normal(p); },
                                     [](vec3 p) { return p.z > -0.5f; });
  const vec3 seed[] = {vec3(0, 0, 1)};
  MarchCounts counts;
  const TriangleMesh m = march(s, vec3(-1), vec3(1), 0.1f, seed, counts);
  const MeshTopology t = topology(m);
  EXPECT_TRUE(t.manifold());
  EXPECT_GT(t.boundary_edges, 20);
  EXPECT_EQ(t.euler_characteristic(), 1);  // a disc
  EXPECT_GT(counts.cubes_refused, 0);
  for (const vec3& p : m.positions) EXPECT_GT(p.z, -0.5f - 0.1f * std::sqrt(3.0f));
}

// A sign that flips where the implicit jumps (two spheres whose insides are told apart by
// a wrong orientation: f jumps from −0.45 to +0.45 on the plane between them) makes no
// surface there.
TEST(MarchingTetrahedra, AJumpOfTheImplicitIsNoSurface) {
  const test::Sphere left{vec3(-1, 0, 0), 0.5f}, right{vec3(1, 0, 0), 0.5f};
  const auto distance = [&](vec3 p) {
    return p.x < 0 ? left.distance(p) : -right.distance(p);  // the right one inside out
  };
  const auto normal = [&](vec3 p) { return p.x < 0 ? left.normal(p) : -right.normal(p); };
  const ImplicitSurface s = analytic(distance, normal);
  const vec3 seeds[] = {vec3(-0.5f, 0, 0), vec3(0.5f, 0, 0), vec3(0.0f, 0, 0)};
  MarchCounts counts;
  const TriangleMesh m = march(s, vec3(-1.6f, -0.6f, -0.6f), vec3(1.6f, 0.6f, 0.6f), 0.1f, seeds, counts);
  const MeshTopology t = topology(m);
  EXPECT_TRUE(t.watertight());
  EXPECT_EQ(t.components, 2);
  EXPECT_EQ(t.euler_characteristic(), 4);
  for (const vec3& p : m.positions) EXPECT_NEAR(std::min(std::abs(left.distance(p)), std::abs(right.distance(p))), 0, 1e-5f);
}

// The same mesh, vertex for vertex, whatever the number of threads.
TEST(MarchingTetrahedra, TheMeshIsTheSameForAnyThreadCount) {
  const test::Torus torus{1.0f, 0.35f};
  const ImplicitSurface s = analytic([&](vec3 p) { return torus.distance(p); }, [&](vec3 p) { return torus.normal(p); });
  const vec3 seed[] = {vec3(1.35f, 0, 0)};
  MarchCounts counts;
  set_cpu_threads(1);
  const TriangleMesh one = march(s, vec3(-1.4f), vec3(1.4f), 0.1f, seed, counts);
  set_cpu_threads(2);
  const TriangleMesh two = march(s, vec3(-1.4f), vec3(1.4f), 0.1f, seed, counts);
  set_cpu_threads(0);
  EXPECT_EQ(one.triangles, two.triangles);
  EXPECT_EQ(one.positions, two.positions);
}

TEST(MarchingTetrahedra, ALatticeTooFineForTheBoxIsRefused) {
  const std::string error = test::error_of([] { lattice_over(vec3(0), vec3(1), 0, 1e-7, "--cell"); });
  EXPECT_NE(error.find("--cell 1e-07 is too small"), std::string::npos) << error;
}

// The band may take three quarters of the memory at kBandBytesPerCube: on this project's
// 24 GiB machine that holds the band of a 10^7-point cloud at the default cell, h/2 (the
// estimate's Σ (h_i/cell)²/3: 4/3 a sample), which a fixed 2^23 refused (2026-11-28).
TEST(MarchingTetrahedra, TheBandsLimitIsAShareOfTheMemory) {
  const std::int64_t gib = std::int64_t(1) << 30;
  const double default_band = 1e7 * (2.0 * 2.0) / 3;
  EXPECT_GT(double(band_cube_limit(24 * gib)), default_band);
  EXPECT_LT(double(band_cube_limit(8 * gib)), default_band);
  EXPECT_LE(double(band_cube_limit(24 * gib)) * kBandBytesPerCube, 0.75 * double(24 * gib));
  EXPECT_GT(double(band_cube_limit(24 * gib)) * kBandBytesPerCube, 0.74 * double(24 * gib));
  EXPECT_EQ(band_cube_limit(-1), kBandCubesWithoutMemory);
  EXPECT_EQ(band_cube_limit(0), kBandCubesWithoutMemory);

  ASSERT_GT(physical_memory_bytes(), 0);  // Linux: sysconf and /proc
  const double over = double(band_cube_limit(physical_memory_bytes())) + 1e3;
  const std::string error = test::error_of([&] { check_band(over, 0.01, "cloud"); });
  EXPECT_NE(error.find("the cell size 0.01 is too small for this cloud"), std::string::npos) << error;
  EXPECT_NE(error.find("of this machine's"), std::string::npos) << error;
  EXPECT_NO_THROW(check_band(over - 2e3, 0.01, "cloud"));
}

// Meshes made by hand: what each count means.
TEST(MeshTopology, CountsWhatIsWrongWithAMesh) {
  TriangleMesh tetrahedron;
  tetrahedron.positions = {vec3(0, 0, 0), vec3(1, 0, 0), vec3(0, 1, 0), vec3(0, 0, 1)};
  tetrahedron.triangles = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}};
  MeshTopology t = topology(tetrahedron);
  EXPECT_TRUE(t.watertight());
  EXPECT_EQ(t.edges, 6);
  EXPECT_EQ(t.euler_characteristic(), 2);

  TriangleMesh flipped = tetrahedron;
  std::swap(flipped.triangles[0][1], flipped.triangles[0][2]);
  t = topology(flipped);
  EXPECT_EQ(t.misoriented_edges, 3);
  EXPECT_FALSE(t.manifold());

  TriangleMesh fin = tetrahedron;  // a third triangle on the edge 0-1
  fin.positions.push_back(vec3(0.5f, -1, 0));
  fin.triangles.push_back({0, 4, 1});
  t = topology(fin);
  EXPECT_EQ(t.non_manifold_edges, 1);
  EXPECT_EQ(t.boundary_edges, 2);

  TriangleMesh bowtie;  // two triangles sharing vertex 0 only
  bowtie.positions = {vec3(0), vec3(1, 0, 0), vec3(1, 1, 0), vec3(-1, 0, 0), vec3(-1, -1, 0), vec3(5)};
  bowtie.triangles = {{0, 1, 2}, {0, 3, 4}};
  t = topology(bowtie);
  EXPECT_EQ(t.non_manifold_vertices, 1);
  EXPECT_EQ(t.components, 2);
  EXPECT_EQ(t.unreferenced_vertices, 1);
  EXPECT_EQ(t.boundary_edges, 6);
}

// The volume a closed mesh encloses, signed by its orientation; open parts enclose none; a
// cavity's surface, facing into it, subtracts.
TEST(MeshTopology, EnclosedVolumeIsSignedByTheOrientation) {
  TriangleMesh m;
  m.positions = {vec3(0, 0, 0), vec3(1, 0, 0), vec3(0, 1, 0), vec3(0, 0, 1)};
  m.normals.assign(4, vec3(0, 0, 1));
  m.triangles = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}};
  EXPECT_NEAR(enclosed_volume(m), 1.0 / 6, 1e-9);
  turn_inside_out(m);
  EXPECT_NEAR(enclosed_volume(m), -1.0 / 6, 1e-9);
  EXPECT_EQ(m.normals[0], vec3(0, 0, -1));
  turn_inside_out(m);
  TriangleMesh cavity = m;  // the same, 8 times larger, around it, facing out: 8/6 − 1/6
  for (vec3& p : cavity.positions) p = 2.0f * p - vec3(0.25f);
  turn_inside_out(m);
  for (const auto& t : m.triangles) cavity.triangles.push_back({t[0] + 4, t[1] + 4, t[2] + 4});
  cavity.positions.insert(cavity.positions.end(), m.positions.begin(), m.positions.end());
  EXPECT_NEAR(enclosed_volume(cavity), 7.0 / 6, 1e-6);
  cavity.triangles.pop_back();  // the inner surface open: it encloses nothing
  EXPECT_NEAR(enclosed_volume(cavity), 8.0 / 6, 1e-6);
}

// A vertex normal facing against its triangles is turned; one facing with them, even 80°
// off them, stays.
TEST(MeshTopology, NormalsFollowTheTrianglesWinding) {
  TriangleMesh m;
  m.positions = {vec3(0, 0, 0), vec3(1, 0, 0), vec3(0, 1, 0), vec3(0, 0, 1)};
  m.triangles = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}};  // outward
  const vec3 out = glm::normalize(vec3(1, 1, 1));
  const vec3 tilted = glm::normalize(out + 5.0f * glm::normalize(vec3(1, -1, 0)));  // 79° from out
  m.normals = {out, vec3(1, 0, 0), vec3(0, -1, 0), tilted};  // the origin's triangles face −out
  EXPECT_EQ(normals_follow_winding(m), 2);
  EXPECT_EQ(m.normals[0], -out);
  EXPECT_EQ(m.normals[1], vec3(1, 0, 0));
  EXPECT_EQ(m.normals[2], vec3(0, 1, 0));
  EXPECT_EQ(m.normals[3], tilted);
}

// Closed parts face out at an even depth and in at an odd one (a cavity's wall): a tetrahedron
// facing in, one inside a larger one facing out (a cavity: in), and a third apart facing
// in are turned to out, in, out; an open part is left as it is.
TEST(MeshTopology, ClosedPartsFaceOutwardByTheirDepth) {
  const std::vector<vec3> corners = {vec3(0, 0, 0), vec3(1, 0, 0), vec3(0, 1, 0), vec3(0, 0, 1)};
  const std::vector<std::array<int, 3>> outward = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}};
  TriangleMesh m;
  auto add = [&](float scale, vec3 shift, bool in, std::size_t faces) {
    const int base = int(m.positions.size());
    for (const vec3& c : corners) {
      m.positions.push_back(scale * c + shift);
      m.normals.push_back(vec3(0, 0, 1));
    }
    for (std::size_t f = 0; f < faces; ++f) {
      const auto& t = outward[f];
      m.triangles.push_back(in ? std::array<int, 3>{base + t[0], base + t[2], base + t[1]}
                               : std::array<int, 3>{base + t[0], base + t[1], base + t[2]});
    }
  };
  add(8, vec3(-1), true, 4);                  // the outer wall, facing in
  add(1, vec3(0.5f), false, 4);               // a cavity inside it, facing out
  add(1, vec3(20, 0, 0), true, 4);            // apart, facing in
  add(1, vec3(40, 0, 0), true, 3);            // open (one face missing): left
  const auto before = m.triangles;
  EXPECT_EQ(face_closed_parts_outward(m), 3);
  TriangleMesh outer = m, cavity = m, apart = m;
  outer.triangles.assign(m.triangles.begin(), m.triangles.begin() + 4);
  cavity.triangles.assign(m.triangles.begin() + 4, m.triangles.begin() + 8);
  apart.triangles.assign(m.triangles.begin() + 8, m.triangles.begin() + 12);
  EXPECT_NEAR(enclosed_volume(outer), 512.0 / 6, 1e-3);
  EXPECT_NEAR(enclosed_volume(cavity), -1.0 / 6, 1e-6);
  EXPECT_NEAR(enclosed_volume(apart), 1.0 / 6, 1e-6);
  EXPECT_EQ(m.normals[0], vec3(0, 0, -1));  // a turned part's normals turn with it
  EXPECT_EQ(m.normals[8], vec3(0, 0, -1));
  EXPECT_EQ(m.normals[12], vec3(0, 0, 1));  // the open part's stay
  EXPECT_TRUE(std::equal(before.begin() + 12, before.end(), m.triangles.begin() + 12));
}

// remove_pinches keeps the larger fan at a pinched vertex and drops unused vertices.
TEST(MeshTopology, RemovePinchesKeepsTheLargestFan) {
  TriangleMesh m;
  m.positions = {vec3(0), vec3(1, 0, 0), vec3(1, 1, 0), vec3(0, 1, 0), vec3(-1, 0, 0), vec3(-1, -1, 0), vec3(9)};
  m.normals.assign(m.positions.size(), vec3(0, 0, 1));
  m.triangles = {{0, 1, 2}, {0, 2, 3}, {0, 4, 5}};  // a fan of two, and one triangle touching at 0
  EXPECT_EQ(remove_pinches(m), 1);
  ASSERT_EQ(m.triangles.size(), 2u);
  EXPECT_EQ(m.positions.size(), 4u);
  EXPECT_EQ(m.normals.size(), 4u);
  const MeshTopology t = topology(m);
  EXPECT_TRUE(t.manifold());
  EXPECT_EQ(t.unreferenced_vertices, 0);
  EXPECT_EQ(m.positions[std::size_t(m.triangles[1][2])], vec3(0, 1, 0));
}

// The mesh of a sampled shape with the defaults `pss mesh` uses.
CloudMesh mesh_of(const PointCloud& cloud, SurfaceOperator surface = SurfaceOperator::mls, float cell = 0,
                  BorderMode borders = BorderMode::clip, Support support = Support::adaptive) {
  MeshParams params;
  params.projection = ProjectionParams::from_h(test::suggested_h(cloud));
  params.projection.support = support;
  params.projection.surface = surface;
  params.projection.borders = borders;
  params.cell = cell;
  Stats stats;
  return mesh_cloud(cloud, params, Backend::cpu, stats);
}

struct Errors {
  float largest_distance = 0, mean_angle = 0, largest_angle = 0;
};
template <class Shape>
Errors errors(const TriangleMesh& m, const Shape& shape) {
  Errors e;
  for (std::size_t i = 0; i < m.positions.size(); ++i) {
    e.largest_distance = std::max(e.largest_distance, std::abs(shape.distance(m.positions[i])));
    const float angle = std::acos(std::clamp(glm::dot(m.normals[i], shape.normal(m.positions[i])), -1.0f, 1.0f));
    e.mean_angle += angle / float(m.positions.size());
    e.largest_angle = std::max(e.largest_angle, angle);
  }
  e.mean_angle *= 180 / 3.14159265f;
  e.largest_angle *= 180 / 3.14159265f;
  return e;
}

// Closed shapes give closed meshes: the sphere's Euler characteristic 2, the torus's 0;
// every vertex on the PSS, with its outward normal; every operator. MLS's and APSS's PSS
// lie within 3e-3 of these clean samples' surface; RIMLS's averaged tangent planes lie
// about h²/(2r) outside a surface of radius r (surface_operators_test.cpp): within h²/r.
TEST(MeshCloud, ClosedShapesGiveWatertightMeshesOnTheSurface) {
  test::SampleOptions o;
  o.count = 6000;
  const PointCloud sphere = test::sample(test::Sphere{}, o);
  o.count = 12000;
  const test::Torus torus{1.0f, 0.35f};
  const PointCloud ring = test::sample(torus, o);
  for (const SurfaceOperator surface : {SurfaceOperator::mls, SurfaceOperator::apss, SurfaceOperator::rimls}) {
    SCOPED_TRACE(surface_name(surface));
    const CloudMesh a = mesh_of(sphere, surface);
    MeshTopology t = topology(a.mesh);
    EXPECT_TRUE(t.watertight());
    EXPECT_EQ(t.components, 1);
    EXPECT_EQ(t.euler_characteristic(), 2);
    const auto tolerance = [&](const PointCloud& cloud, float radius) {
      const float h = test::suggested_h(cloud);
      return surface == SurfaceOperator::rimls ? h * h / radius : 3e-3f;
    };
    Errors e = errors(a.mesh, test::Sphere{});
    EXPECT_LT(e.largest_distance, tolerance(sphere, 1.0f));
    EXPECT_LT(e.mean_angle, 1.0f);
    EXPECT_LT(e.largest_angle, 8.0f);
    for (const auto& tri : a.mesh.triangles)
      ASSERT_GT(glm::dot(face_normal(a.mesh, tri), a.mesh.positions[std::size_t(tri[0])]), 0.0f);
    EXPECT_EQ(test::crossing_triangle_pairs(a.mesh), 0);

    const CloudMesh b = mesh_of(ring, surface);
    t = topology(b.mesh);
    EXPECT_TRUE(t.watertight());
    EXPECT_EQ(t.components, 1);
    EXPECT_EQ(t.euler_characteristic(), 0);
    EXPECT_EQ(test::crossing_triangle_pairs(b.mesh), 0);
    e = errors(b.mesh, torus);
    EXPECT_LT(e.largest_distance, tolerance(ring, torus.minor));
    EXPECT_LT(e.mean_angle, 1.5f);
  }
}

// A noisy sphere (noise about h/10, the normals estimated): the vertices take RIMLS's
// filtered normals (robust_implicit.hpp), as `pss project`'s points do, not ∇f's.
TEST(MeshCloud, ANoisySpheresVerticesTakeTheFilteredNormals) {
  test::SampleOptions o;
  o.count = 20000;
  o.noise = 0.005f;
  PointCloud cloud = test::sample(test::Sphere{}, o);
  cloud.normals.clear();
  const CloudMesh m = mesh_of(cloud, SurfaceOperator::rimls);
  // ∇f's: 2.08°; the filtered: 1.46°.
  EXPECT_LT(errors(m.mesh, test::Sphere{}).mean_angle, 1.75f);
}

// Noise of 0.4 h: the fits wrap a sample a few σ off the sphere in a bubble of its own (19
// here), each held by fewer than three samples. With one h: the adaptive widths, which
// follow the noise (support.hpp), leave fewer bubbles to remove.
TEST(MeshCloud, BubblesAroundNoisySamplesAreRemoved) {
  test::SampleOptions o;
  o.count = 12000;
  o.noise = 0.03f;
  const CloudMesh m =
      mesh_of(test::sample(test::Sphere{}, o), SurfaceOperator::mls, 0, BorderMode::extend, Support::global);
  const MeshTopology t = topology(m.mesh);
  EXPECT_GE(m.counts.unsupported_parts, 5);
  EXPECT_EQ(t.components, 1);
  EXPECT_TRUE(t.watertight());
  EXPECT_EQ(t.unreferenced_vertices, 0);
}

// A part as small as the data can make, a sphere of radius 3h beside a larger one, is held
// by its own samples and stays.
TEST(MeshCloud, ASmallPartHeldByItsSamplesStays) {
  test::SampleOptions o;
  o.count = 6000;
  PointCloud cloud = test::sample(test::Sphere{}, o);
  const float h = test::suggested_h(cloud);
  o.count = std::size_t(6000 * 9 * h * h);  // the same density on a radius of 3h
  const PointCloud small = test::sample(test::Sphere{vec3(2, 0, 0), 3 * h}, o);
  cloud.positions.insert(cloud.positions.end(), small.positions.begin(), small.positions.end());
  const CloudMesh m = mesh_of(cloud);
  const MeshTopology t = topology(m.mesh);
  EXPECT_EQ(m.counts.unsupported_parts, 0);
  EXPECT_EQ(t.components, 2);
  EXPECT_TRUE(t.watertight());
}

// A box with a bore (issue 26's CAD part, sampled with its exact normals): a closed surface
// of genus one, so χ = 0, with creases; MLS's and RIMLS's meshes are one watertight
// component, on the faces away from the creases (farther than 2h from an edge or rim).
TEST(MeshCloud, ABoxWithABoreIsOneClosedSurfaceOfGenusOne) {
  const test::BoredBox box;
  const PointCloud cloud = test::sample(box, 0.04f);
  const float h = test::suggested_h(cloud);
  for (const SurfaceOperator surface : {SurfaceOperator::mls, SurfaceOperator::rimls}) {
    SCOPED_TRACE(surface_name(surface));
    const CloudMesh m = mesh_of(cloud, surface);
    test::expect_one_closed_surface(m.mesh, 0);
    EXPECT_GT(enclosed_volume(m.mesh), 0);
    float worst = 0;
    for (const vec3& p : m.mesh.positions)
      if (box.to_crease(p) > 2 * h) worst = std::max(worst, std::abs(box.distance(p)));
    // RIMLS lies about h²/(2r) outside the bore's wall of radius r (as on the sphere above).
    EXPECT_LT(worst, surface == SurfaceOperator::rimls ? h * h / box.bore : 0.05f * h);
  }
}

// Each vertex is the root of the implicit on its edge, to a thousandth of the cell (its
// tolerance; float rounding of the projection adds a little), but where the root lies
// within kEdgeMargin of an end of its edge: there the vertex stays that far inside, next
// to a corner of the lattice (cloud_lattice, as mesh_cloud lays it). APSS reproduces a
// sphere sampled with its exact normals exactly (surface_operators_test.cpp), so the
// vertices lie on the sphere to that.
TEST(MeshCloud, EveryVertexIsARootOnItsEdge) {
  test::SampleOptions o;
  o.count = 6000;
  PointCloud sphere = test::sample(test::Sphere{}, o);
  sphere.normals = sphere.positions;
  const CloudMesh m = mesh_of(sphere, SurfaceOperator::apss);
  const UnitFrame frame = unit_frame(sphere.positions);
  const Lattice lattice =
      cloud_lattice(sphere.bounds(), frame, BorderMode::clip, 0, double(m.cell) / frame.scale, false);
  float worst = 0, worst_clamped = 0;
  std::size_t clamped = 0;
  for (const vec3& p : m.mesh.positions) {
    const float error = std::abs(glm::length(p) - 1);
    const glm::dvec3 steps = (glm::dvec3(frame.to_unit(p)) - lattice.origin) / lattice.cell;
    const bool near_corner = glm::length(steps - glm::round(steps)) < 1.1 * kEdgeMargin * std::sqrt(3.0);
    (near_corner ? worst_clamped : worst) = std::max(near_corner ? worst_clamped : worst, error);
    clamped += near_corner;
  }
  EXPECT_LT(worst, 2e-3f * m.cell);
  EXPECT_LT(worst_clamped, (kEdgeMargin * std::sqrt(3.0f) + 2e-3f) * m.cell);
  EXPECT_LT(clamped, m.mesh.positions.size() / 20);
  EXPECT_EQ(test::crossing_triangle_pairs(m.mesh), 0);
}

// A part thinner than the fits' support (two faces 0.06 apart, ρ about 0.1), its exact
// normals in the file: both faces and the rim, closed, on the surface, facing out, with the
// operators that keep a thin part's faces apart (the paper's MLS fits one plane across
// both: surface_operators_test.cpp). Corners between the faces may lie nearer one face's
// samples than the face their projection reaches.
TEST(MeshCloud, AThinClosedPartKeepsBothFaces) {
  const test::Pill pill{1.0f, 0.03f};
  test::SampleOptions o;
  o.count = 30000;
  const PointCloud cloud = test::sample(pill, o);
  ASSERT_GT(2 * test::suggested_h(cloud), 2 * pill.half);
  for (const SurfaceOperator surface : {SurfaceOperator::apss, SurfaceOperator::rimls}) {
    SCOPED_TRACE(surface_name(surface));
    const CloudMesh m = mesh_of(cloud, surface);
    test::expect_one_closed_surface(m.mesh, 2);
    std::size_t far = 0, inward = 0;
    for (std::size_t i = 0; i < m.mesh.positions.size(); ++i) {
      const vec3 p = m.mesh.positions[i];
      far += std::abs(pill.distance(p)) > 0.01f;
      inward += glm::dot(m.mesh.normals[i], pill.normal(p)) < 0.5f;
    }
    EXPECT_LT(far, m.mesh.positions.size() / 100);
    EXPECT_LT(inward, m.mesh.positions.size() / 100);
  }
}

// The bunny scan (its base has holes, its ear tips open): one manifold component, no two
// triangles crossing, only the data's own holes and a
// few small ones open; orientation taken where the surface point lies, not where the
// corner does, keeps its thin ears whole (at the corner: 5 components, χ = -117).
TEST(MeshCloud, TheBunnyIsOneManifoldComponent) {
  const PointCloud bunny = read_point_cloud(PSS_SOURCE_DIR "/data/bun_zipper.ply");
  const CloudMesh m = mesh_of(bunny);
  const MeshTopology t = topology(m.mesh);
  EXPECT_TRUE(t.manifold());
  EXPECT_EQ(t.components, 1);
  EXPECT_GT(t.euler_characteristic(), -40);  // 2 − (boundary loops) − 2·genus
  EXPECT_EQ(test::crossing_triangle_pairs(m.mesh), 0);
  // Every vertex normal faces with its triangles (before they were turned, 181 did not: at
  // the ears' rims the fits' normals follow the other sheet).
  std::vector<glm::dvec3> faces(m.mesh.positions.size(), glm::dvec3(0.0));
  for (const auto& tri : m.mesh.triangles) {
    const glm::dvec3 a(m.mesh.positions[std::size_t(tri[0])]), b(m.mesh.positions[std::size_t(tri[1])]),
        c(m.mesh.positions[std::size_t(tri[2])]);
    for (const int v : tri) faces[std::size_t(v)] += glm::cross(b - a, c - a);
  }
  std::size_t against = 0;
  for (std::size_t v = 0; v < faces.size(); ++v) against += glm::dot(faces[v], glm::dvec3(m.mesh.normals[v])) < 0;
  EXPECT_EQ(against, 0u);
  EXPECT_GT(m.counts.normals_turned, 0);
}

// The cell sets the triangles' size: half the cell, about four times the triangles.
TEST(MeshCloud, TheCellSetsTheResolution) {
  test::SampleOptions o;
  o.count = 6000;
  const PointCloud sphere = test::sample(test::Sphere{}, o);
  const CloudMesh coarse = mesh_of(sphere, SurfaceOperator::mls, 0.09f), fine = mesh_of(sphere, SurfaceOperator::mls, 0.045f);
  EXPECT_EQ(coarse.cell, 0.09f);
  const double ratio = double(fine.mesh.triangles.size()) / double(coarse.mesh.triangles.size());
  EXPECT_GT(ratio, 3.5);
  EXPECT_LT(ratio, 4.5);
  EXPECT_TRUE(topology(fine.mesh).watertight());
  // The default: half the h of the spacing.
  EXPECT_FLOAT_EQ(mesh_of(sphere).cell, kDefaultCellPerH * test::suggested_h(sphere));
}

// A cube the surface crosses has corners a diagonal, √3 cells, off it, and a corner needs
// samples within its support: a cell over ρ/2 is refused, with the largest that serves (at
// 0.55ρ this sphere opened, and the bunny broke apart at 0.9ρ); it is one closed
// surface at 0.45ρ, and one piece at ρ/2 (where the lattice's corners fall decides the last
// few edges: half a cube off the box's faces, 3 edges open on this sphere; 0.48ρ closed).
TEST(MeshCloud, ACellWhoseCornersLeaveTheSupportsIsRefused) {
  test::SampleOptions o;
  o.count = 6000;
  const PointCloud sphere = test::sample(test::Sphere{}, o);
  const float largest = 0.5f * ProjectionParams::from_h(test::suggested_h(sphere)).rho;
  try {
    mesh_of(sphere, SurfaceOperator::mls, 1.01f * largest);
    ADD_FAILURE() << "a cell over rho/2 was taken";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("larger than rho/2 = " + format_number(largest)), std::string::npos)
        << e.what();
  }
  const CloudMesh closed = mesh_of(sphere, SurfaceOperator::mls, 0.9f * largest);
  EXPECT_TRUE(topology(closed.mesh).watertight());
  EXPECT_EQ(topology(closed.mesh).components, 1);
  EXPECT_EQ(topology(mesh_of(sphere, SurfaceOperator::mls, largest).mesh).components, 1);
}

// An open sheet's mesh ends where its samples end (clip), with one boundary; extend runs on
// past them as the projection extrapolates.
TEST(MeshCloud, AnOpenSheetEndsAtItsSamples) {
  test::SampleOptions o;
  o.count = 4000;
  const PointCloud square = test::sample_plane(1.0f, o);
  const CloudMesh clipped = mesh_of(square), extended = mesh_of(square, SurfaceOperator::mls, 0, BorderMode::extend);
  for (const CloudMesh* m : {&clipped, &extended}) {
    const MeshTopology t = topology(m->mesh);
    EXPECT_TRUE(t.manifold());
    EXPECT_EQ(t.components, 1);
    EXPECT_EQ(t.euler_characteristic(), 1);  // a disc
    for (const vec3& p : m->mesh.positions) ASSERT_NEAR(p.z, 0.0f, (kEdgeMargin * std::sqrt(3.0f) + 1e-3f) * m->cell);
  }
  float reach_clipped = 0, reach_extended = 0;
  for (const vec3& p : clipped.mesh.positions) reach_clipped = std::max({reach_clipped, std::abs(p.x), std::abs(p.y)});
  for (const vec3& p : extended.mesh.positions) reach_extended = std::max({reach_extended, std::abs(p.x), std::abs(p.y)});
  EXPECT_LT(reach_clipped, 1.0f + clipped.cell);
  EXPECT_GT(reach_extended, 1.0f + 2 * extended.cell);
}

// A hole in a sheet whose rim's supports span it (radius 1.6 h, under ρ = 2h) stays open when
// clipped: its middle lies among the samples, but farther than their widths from any (the
// bunny's base: lids across its holes' narrows, pierced at fine cells). No vertex of the
// annulus lies farther than h from the samples.
TEST(MeshCloud, AHoleTheSupportsSpanStaysOpen) {
  test::SampleOptions o;
  o.count = 4000;
  const PointCloud square = test::sample_plane(1.0f, o);
  const float h = test::suggested_h(square);
  PointCloud holed;
  for (const vec3& p : square.positions)
    if (glm::length(vec2(p)) > 1.6f * h) holed.positions.push_back(p);
  const CloudMesh m = mesh_of(holed);
  ASSERT_NEAR(test::suggested_h(holed), h, 0.05f * h);
  const MeshTopology t = topology(m.mesh);
  EXPECT_TRUE(t.manifold());
  EXPECT_EQ(t.components, 1);
  EXPECT_EQ(t.euler_characteristic(), 0);  // an annulus; a lid made it a disc
  float farthest = 0;
  for (const vec3& v : m.mesh.positions) {
    float nearest = kInfinity;
    for (const vec3& p : holed.positions) nearest = std::min(nearest, glm::length(v - p));
    farthest = std::max(farthest, nearest);
  }
  EXPECT_LT(farthest, 1.05f * h);
}

// Where a file's normals were turned (a flipped part of a sheet), which side is out is a
// guess, and the closed parts' volume decides it only where they are most of the mesh: a
// small blob facing inward above a large open sheet turns itself outward (its depth), not the
// sheet downward.
TEST(MeshCloud, AFewClosedBlobsDoNotTurnAMostlyOpenMesh) {
  test::SampleOptions o;
  o.count = 6000;
  PointCloud cloud = test::sample_plane(1.0f, o);
  cloud.normals.resize(cloud.size());
  for (std::size_t i = 0; i < cloud.size(); ++i)
    cloud.normals[i] = vec3(0, 0, cloud.positions[i].x < 0.4f ? 1.0f : -1.0f);  // a flipped part: turned
  const test::Sphere blob{vec3(0, 0, 0.6f), 0.15f};
  o.count = 500;
  const PointCloud ball = test::sample(blob, o);
  for (std::size_t i = 0; i < ball.size(); ++i) {
    cloud.positions.push_back(ball.positions[i]);
    cloud.normals.push_back(-blob.normal(ball.positions[i]));  // inward, all alike: nothing to turn
  }
  const CloudMesh m = mesh_of(cloud);
  EXPECT_GT(m.normals_turned, 0u);
  EXPECT_FALSE(m.turned_outward);
  EXPECT_EQ(m.counts.closed_parts_turned, 1);
  std::size_t sheet = 0, sheet_down = 0, ball_vertices = 0, ball_in = 0;
  for (std::size_t v = 0; v < m.mesh.positions.size(); ++v) {
    const vec3 p = m.mesh.positions[v], n = m.mesh.normals[v];
    if (p.z > 0.3f) {
      ++ball_vertices;
      ball_in += glm::dot(n, p - blob.center) < 0;
    } else {
      ++sheet;
      sheet_down += n.z < 0;
    }
  }
  EXPECT_GT(sheet, 1000u);
  EXPECT_EQ(sheet_down, 0u);
  EXPECT_GT(ball_vertices, 100u);
  EXPECT_EQ(ball_in, 0u);
}

// A flat face on the cloud's box (a CAD part's base, exact to the last bit) lay on a plane of
// the lattice's corners, where f is zero give or take its rounding: no cube crossed it, and
// the face was not meshed (a sheet with a ball above it, at z = 0.05 or 0.3337; at 0 the
// corners' f was exactly zero and it was). Whatever its height, it is.
TEST(MeshCloud, AFlatFaceOnTheBoxIsMeshed) {
  for (const float z : {0.05f, 0.3337f}) {
    SCOPED_TRACE(z);
    PointCloud cloud = test::sheet_and_ball(4000, test::Sphere{vec3(0, 0, 0.6f), 0.15f}, 400);
    for (vec3& p : cloud.positions) p.z += z;
    const CloudMesh m = mesh_of(cloud);
    std::size_t on_face = 0;
    for (const vec3& p : m.mesh.positions) on_face += std::abs(p.z - z) < 1e-4f;
    EXPECT_GT(on_face, 2000u) << "the face was not meshed";
    EXPECT_EQ(topology(m.mesh).components, 2);
  }
}

TEST(MeshCloud, TooFewPointsOrABadCellAreRefused) {
  PointCloud two;
  two.positions = {vec3(0), vec3(1)};
  EXPECT_NE(test::error_of([&] { mesh_of(two); }).find("at least 3 points"), std::string::npos);
  test::SampleOptions o;
  o.count = 500;
  const PointCloud sphere = test::sample(test::Sphere{}, o);
  for (const float cell : {-1.0f, std::nanf("")})
    EXPECT_NE(test::error_of([&] { mesh_of(sphere, SurfaceOperator::mls, cell); }).find("cell size must be a positive"),
              std::string::npos) << cell;
}

}  // namespace
}  // namespace pss
