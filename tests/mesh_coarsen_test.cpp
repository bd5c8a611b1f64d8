// The marched mesh made as coarse as its data (issue 27, coarsen.hpp): on analytic implicits
// the topology, the vertices (the march's, on the surface), the boundary, the creases and the
// curvature stay; the triangles grow to the cell asked of each vertex. Then a cloud whose
// spacing steps 8:1 meshed with triangles that follow it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <numbers>
#include <random>
#include <span>
#include <utility>

#include "pss/backend/backend.hpp"
#include "pss/core/error.hpp"
#include "pss/mesh/coarsen.hpp"
#include "pss/mesh/mesh_cloud.hpp"
#include "support/analytic_implicit.hpp"
#include "support/mesh_checks.hpp"
#include "support/self_intersection.hpp"
#include "support/shapes.hpp"

namespace pss {
namespace {

using test::analytic;
using test::march;
using test::triangle_quality;

// coarsen_mesh's count of the vertices it removed.
std::int64_t coarsened(TriangleMesh& m, std::span<const float> cell) {
  MarchCounts counts;
  coarsen_mesh(m, cell, counts);
  return counts.collapsed_vertices;
}

glm::dvec3 centroid(const TriangleMesh& m, const std::array<int, 3>& t) {
  return (glm::dvec3(m.positions[std::size_t(t[0])]) + glm::dvec3(m.positions[std::size_t(t[1])]) +
          glm::dvec3(m.positions[std::size_t(t[2])])) /
         3.0;
}

double area(const TriangleMesh& m) {
  double sum = 0;
  for (const auto& t : m.triangles) {
    const glm::dvec3 a(m.positions[std::size_t(t[0])]);
    sum += 0.5 * glm::length(glm::cross(glm::dvec3(m.positions[std::size_t(t[1])]) - a,
                                        glm::dvec3(m.positions[std::size_t(t[2])]) - a));
  }
  return sum;
}

// The mean length of the edges whose midpoints `where` takes.
template <class Where>
double mean_edge(const TriangleMesh& m, Where where) {
  double sum = 0;
  int n = 0;
  for (const auto& t : m.triangles)
    for (int k = 0; k < 3; ++k) {
      const vec3 a = m.positions[std::size_t(t[std::size_t(k)])], b = m.positions[std::size_t(t[std::size_t((k + 1) % 3)])];
      if (!where(0.5f * (a + b))) continue;
      sum += double(glm::length(a - b));
      ++n;
    }
  return sum / std::max(n, 1);
}

// A unit sphere off the lattice's symmetry, marched in cubes of `cell`.
const test::Sphere kSphere{vec3(0.013f, -0.021f, 0.007f), 1.0f};
TriangleMesh marched_sphere(float cell) {
  const ImplicitSurface s =
      analytic([&](vec3 p) { return kSphere.distance(p); }, [&](vec3 p) { return kSphere.normal(p); });
  const vec3 seed[] = {kSphere.center + vec3(1, 0, 0)};
  MarchCounts counts;
  return march(s, vec3(-1.1f), vec3(1.1f), cell, seed, counts);
}

// At the march's own cell the slivers go (triangles with a vertex near another) and the
// edges, from near 0 to √3 cells, come to about the cell: every vertex left is one the march
// placed, the sphere stays one closed surface facing out, no triangle worse shaped than the
// worst before.
TEST(Coarsen, AtTheMarchsCellTheSliversGoAndTheSphereStaysClosed) {
  TriangleMesh m = marched_sphere(0.1f);
  const TriangleMesh before = m;
  double worst_before = 1;
  int slivers_before = 0;
  for (const auto& t : before.triangles) {
    worst_before = std::min(worst_before, triangle_quality(before, t));
    slivers_before += triangle_quality(before, t) < 0.15;
  }
  ASSERT_GT(slivers_before, 20);
  const auto everywhere = [](vec3) { return true; };
  const double edge_before = mean_edge(before, everywhere);
  const std::vector<float> cell(m.positions.size(), 0.1f);
  const std::int64_t removed = coarsened(m, cell);
  EXPECT_EQ(std::int64_t(before.positions.size()) - removed, std::int64_t(m.positions.size()));
  EXPECT_GT(removed, 0);
  EXPECT_LT(edge_before, 0.07);
  EXPECT_GT(mean_edge(m, everywhere), 0.08);
  EXPECT_LT(mean_edge(m, everywhere), 0.13);

  const MeshTopology t = topology(m);
  EXPECT_TRUE(t.watertight());
  EXPECT_EQ(t.components, 1);
  EXPECT_EQ(t.euler_characteristic(), 2);
  EXPECT_EQ(t.unreferenced_vertices, 0);
  EXPECT_EQ(test::crossing_triangle_pairs(m), 0);
  // The vertices kept are the march's, in its order, with their normals.
  ASSERT_EQ(m.normals.size(), m.positions.size());
  std::size_t j = 0;
  for (std::size_t i = 0; i < m.positions.size(); ++i, ++j) {
    while (j < before.positions.size() && before.positions[j] != m.positions[i]) ++j;
    ASSERT_LT(j, before.positions.size()) << "vertex " << i << " is not the march's";
    EXPECT_EQ(m.normals[i], before.normals[j]);
  }
  int slivers = 0;
  for (const auto& tri : m.triangles) {
    EXPECT_GE(triangle_quality(m, tri), worst_before - 1e-9);
    slivers += triangle_quality(m, tri) < 0.15;
    EXPECT_GT(glm::dot(glm::cross(m.positions[std::size_t(tri[1])] - m.positions[std::size_t(tri[0])],
                                  m.positions[std::size_t(tri[2])] - m.positions[std::size_t(tri[0])]),
                       m.positions[std::size_t(tri[0])] - kSphere.center),
              0.0f);
  }
  EXPECT_LT(slivers, slivers_before / 4);
}

// A cell far larger than the curvature allows: the triangles stop where their planes would
// leave the sphere by a share of it; without that test they grow until the sphere is a
// few dozen faces.
TEST(Coarsen, CurvatureStopsTheTrianglesGrowth) {
  TriangleMesh m = marched_sphere(0.05f);
  const std::size_t before = m.triangles.size();
  const float cell = 1.0f;
  coarsened(m, std::vector<float>(m.positions.size(), cell));
  double farthest = 0;
  for (const auto& t : m.triangles)
    farthest = std::max(farthest, std::abs(glm::length(centroid(m, t) - glm::dvec3(kSphere.center)) - 1.0));
  EXPECT_LT(farthest, 4 * kCoarseningError * cell);
  EXPECT_LT(m.triangles.size(), before / 4);
  const MeshTopology t = topology(m);
  EXPECT_TRUE(t.watertight());
  EXPECT_EQ(t.euler_characteristic(), 2);
  EXPECT_EQ(test::crossing_triangle_pairs(m), 0);
}

// A box, its edges and corners put on by the march (creases.hpp), at three times the
// march's cell: the faces coarsen, the edges stay within the share of the cell allowed.
TEST(Coarsen, ABoxsFacesCoarsenItsEdgesStay) {
  const vec3 half(0.5f, 0.4f, 0.3f), center(0.011f, -0.017f, 0.006f);
  const auto distance = [&](vec3 p) {
    const vec3 q = glm::abs(p - center) - half;
    return glm::length(glm::max(q, vec3(0))) + std::min(std::max(q.x, std::max(q.y, q.z)), 0.0f);
  };
  const auto normal = [&](vec3 p) {  // the nearest face's, outside as inside
    const vec3 q = glm::abs(p - center) - half, s = glm::sign(p - center);
    const vec3 outside = glm::max(q, vec3(0));
    if (glm::length(outside) > 0) return glm::normalize(outside * s);
    return q.x >= q.y && q.x >= q.z ? vec3(s.x, 0, 0) : q.y >= q.z ? vec3(0, s.y, 0) : vec3(0, 0, s.z);
  };
  const vec3 seed[] = {center + vec3(half.x, 0, 0)};
  MarchCounts counts;
  TriangleMesh m = march(analytic(distance, normal), vec3(-0.7f), vec3(0.7f), 0.04f, seed, counts);
  ASSERT_GT(counts.crease_vertices, 50);
  const double area_before = area(m);
  const std::size_t before = m.triangles.size();
  double farthest_before = 0;
  for (const auto& t : m.triangles) farthest_before = std::max(farthest_before, double(std::abs(distance(vec3(centroid(m, t))))));
  ASSERT_LT(farthest_before, 1e-5);  // the march's box is the box
  const float cell = 0.12f;
  coarsened(m, std::vector<float>(m.positions.size(), cell));
  double farthest = 0;
  for (const auto& t : m.triangles) farthest = std::max(farthest, double(std::abs(distance(vec3(centroid(m, t))))));
  EXPECT_LT(double(m.triangles.size()), double(before) / 2.5);
  EXPECT_LT(farthest, 2 * kCoarseningError * cell);
  EXPECT_NEAR(area(m), area_before, 2e-3 * area_before);
  const MeshTopology t = topology(m);
  EXPECT_TRUE(t.watertight());
  EXPECT_EQ(t.euler_characteristic(), 2);
}

// An open square sheet marched in cubes of 0.02 whose cell steps 8:1 across x = 0: the
// triangles come to each side's cell, the outline (boundary) stays, so does the area.
TEST(Coarsen, TrianglesFollowTheCellAndTheOutlineStays) {
  const float z = 0.0123f;
  const auto inside = [](vec3 p) { return std::abs(p.x) < 0.8f && std::abs(p.y) < 0.8f; };
  const ImplicitSurface sheet = analytic([&](vec3 p) { return p.z - z; }, [](vec3) { return vec3(0, 0, 1); }, inside);
  const vec3 seed[] = {vec3(0.1f, 0.1f, z)};
  MarchCounts counts;
  TriangleMesh m = march(sheet, vec3(-1), vec3(1), 0.02f, seed, counts);
  std::vector<float> cell(m.positions.size());
  for (std::size_t v = 0; v < cell.size(); ++v) cell[v] = m.positions[v].x < 0 ? 0.02f : 0.16f;
  const double area_before = area(m);
  const MeshTopology shape_before = topology(m);
  const auto fine = [](vec3 p) { return p.x < -0.2f; };
  const auto coarse = [](vec3 p) { return p.x > 0.2f; };
  const auto beside_the_step = [](vec3 p) { return p.x > -0.03f && p.x < 0; };  // fine, by coarse
  const double fine_before = mean_edge(m, fine), coarse_before = mean_edge(m, coarse);
  coarsened(m, cell);
  EXPECT_LT(fine_before, 0.7 * 0.02);
  EXPECT_LT(coarse_before, 0.7 * 0.02);
  EXPECT_NEAR(mean_edge(m, fine), 0.02, 0.005);
  EXPECT_LT(mean_edge(m, beside_the_step), 0.027);  // an edge is short by the finer cell of its ends
  EXPECT_NEAR(mean_edge(m, coarse), 0.16, 0.04);
  EXPECT_NEAR(area(m), area_before, 1e-4 * area_before);
  for (const vec3& p : m.positions) ASSERT_NEAR(p.z, z, 1e-6f);
  const MeshTopology t = topology(m);
  EXPECT_TRUE(t.manifold());
  EXPECT_EQ(t.components, 1);
  EXPECT_EQ(t.euler_characteristic(), shape_before.euler_characteristic());
  EXPECT_LT(t.boundary_edges, shape_before.boundary_edges);
  EXPECT_EQ(test::crossing_triangle_pairs(m), 0);
}

// An n × n grid of cells over the unit square, each split by its rising diagonal, its
// vertex (i, j) at place(i/n, j/n) and index j(n + 1) + i.
template <class Place>
TriangleMesh grid_sheet(int n, Place place) {
  TriangleMesh m;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) m.positions.push_back(place(float(i) / float(n), float(j) / float(n)));
  const auto at = [&](int i, int j) { return j * (n + 1) + i; };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      m.triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      m.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    }
  return m;
}

// A square of 20 × 20 cells, each split by its rising diagonal, and a cell 10 times its side:
// the straight stretches of the outline coarsen, the corners stay, so does the area, exactly.
TEST(Coarsen, ASquaresCornersStay) {
  const int n = 20;
  TriangleMesh m = grid_sheet(n, [](float x, float y) { return vec3(x, y, 0); });
  EXPECT_GT(coarsened(m, std::vector<float>(m.positions.size(), 0.5f)), 0);
  EXPECT_NEAR(area(m), 1.0, 1e-6);
  const MeshTopology t = topology(m);
  EXPECT_TRUE(t.manifold());
  EXPECT_EQ(t.euler_characteristic(), 1);
  EXPECT_LT(t.boundary_edges, 4 * n);
}

// A sheet of 48,841 vertices, so many that the coarsening splits it into blocks that cores
// take in turn (coarsen.cpp): on 1, 2 and 3 threads the same mesh, and as coarse across the
// blocks' borders as within them: no edge is left shorter than the share of the cell that
// collapses but at the outline, whose corners stay. Left to the blocks alone, the edges
// across their borders would stay short.
TEST(Coarsen, ALargeSheetCoarsensTheSameOnAnyThreadsAndAsCoarseAcrossItsBlocks) {
  const int n = 220;
  const TriangleMesh sheet = grid_sheet(n, [](float x, float y) { return vec3(x, y, 0); });
  const float side = 4.0f / float(n);
  const std::vector<float> cell(sheet.positions.size(), side);
  std::vector<TriangleMesh> meshes;
  const int threads_before = cpu_threads();
  for (const int threads : {1, 2, 3}) {
    set_cpu_threads(threads);
    TriangleMesh m = sheet;
    EXPECT_GT(coarsened(m, cell), 0);
    meshes.push_back(std::move(m));
  }
  set_cpu_threads(threads_before);
  for (std::size_t k = 1; k < meshes.size(); ++k) {
    EXPECT_EQ(meshes[k].positions, meshes[0].positions) << k + 1 << " threads";
    EXPECT_EQ(meshes[k].triangles, meshes[0].triangles) << k + 1 << " threads";
  }
  const TriangleMesh& m = meshes[0];
  const auto inner = [](vec3 p) { return std::min(std::min(p.x, 1 - p.x), std::min(p.y, 1 - p.y)) > 0.05f; };
  int short_edges = 0, edges = 0;
  for (const auto& t : m.triangles)
    for (int k = 0; k < 3; ++k) {
      const vec3 a = m.positions[std::size_t(t[std::size_t(k)])];
      const vec3 b = m.positions[std::size_t(t[std::size_t((k + 1) % 3)])];
      if (!inner(a) || !inner(b)) continue;
      ++edges;
      short_edges += glm::length(a - b) < kShortEdgeShare * side;
    }
  std::printf("%d of %d inner edges shorter than %g cells\n", short_edges, edges, double(kShortEdgeShare));
  EXPECT_GT(edges, 1000);
  EXPECT_LT(short_edges, edges / 100);
  EXPECT_NEAR(area(m), 1.0, 1e-5);
  const MeshTopology t = topology(m);
  EXPECT_TRUE(t.manifold());
  EXPECT_EQ(t.euler_characteristic(), 1);
  EXPECT_EQ(test::crossing_triangle_pairs(m), 0);
}

// The distance from x to the nearest edge of m that lies in one triangle only.
double distance_to_boundary(const TriangleMesh& m, const glm::dvec3& x) {
  std::map<std::pair<int, int>, int> uses;
  for (const auto& t : m.triangles)
    for (int k = 0; k < 3; ++k) ++uses[std::minmax(t[std::size_t(k)], t[std::size_t((k + 1) % 3)])];
  double nearest = 1e300;
  for (const auto& [edge, n] : uses) {
    if (n != 1) continue;
    const glm::dvec3 a(m.positions[std::size_t(edge.first)]), b(m.positions[std::size_t(edge.second)]);
    const double t = std::clamp(glm::dot(x - a, b - a) / glm::dot(b - a, b - a), 0.0, 1.0);
    nearest = std::min(nearest, glm::length(x - (a + t * (b - a))));
  }
  return nearest;
}

// A flat sheet whose upper rim is an arc, y = 1 + 0.5 sin(πx): the rim's vertices go where
// the rim is straight enough, and every vertex of the rim as it was stays within the
// tolerance (0.02 cell) of the rim as it is, however many collapses took it in.
TEST(Coarsen, ACurvedRimStaysWithinTheTolerance) {
  const int n = 60;
  TriangleMesh m = grid_sheet(n, [](float x, float y) {
    return vec3(x, y * (1 + 0.5f * std::sin(std::numbers::pi_v<float> * x)), 0);
  });
  const TriangleMesh before = m;
  const float cell = 0.1f;
  EXPECT_GT(coarsened(m, std::vector<float>(m.positions.size(), cell)), 0);
  EXPECT_LT(topology(m).boundary_edges, 4 * n);
  double farthest = 0;
  for (int i = 0; i <= n; ++i)
    farthest = std::max(farthest, distance_to_boundary(m, glm::dvec3(before.positions[std::size_t(n * (n + 1) + i)])));
  EXPECT_LE(farthest, kCoarseningError * cell + 1e-6);
  EXPECT_EQ(topology(m).euler_characteristic(), 1);
}

// A lone sliver, its apex within the tolerance of its base: collapsing the apex would take
// the only triangle with it, and the part would vanish. It stays.
TEST(Coarsen, ALoneSliverIsNotCollapsedAway) {
  TriangleMesh m;
  m.positions = {vec3(0, 0, 0), vec3(1, 0, 0), vec3(0.5f, 0.001f, 0)};
  m.triangles = {{0, 1, 2}};
  EXPECT_EQ(coarsened(m, std::vector<float>(3, 10.0f)), 0);
  EXPECT_EQ(m.triangles.size(), 1u);
}

// A closed tetrahedron, flat and small against its cell: each edge passes the link condition
// (its ends share just the edge's two opposite corners), but a collapse would fold the rest
// onto one double-sided triangle. It stays as it is.
TEST(Coarsen, ATetrahedronDoesNotFoldFlat) {
  TriangleMesh m;
  m.positions = {vec3(-1, 0, 0), vec3(1, 0, 0), vec3(0, 1, 0), vec3(0, 1, 0.3f)};
  m.triangles = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}};
  ASSERT_TRUE(topology(m).watertight());
  EXPECT_EQ(coarsened(m, std::vector<float>(4, 100.0f)), 0);
  EXPECT_EQ(m.triangles.size(), 4u);
  EXPECT_TRUE(topology(m).watertight());
}

TEST(Coarsen, CellsMustBeOneAVertexAndPositiveAndPlacesFinite) {
  TriangleMesh m = marched_sphere(0.2f);
  EXPECT_THROW(coarsened(m, std::vector<float>(m.positions.size() - 1, 0.2f)), Error);
  std::vector<float> cell(m.positions.size(), 0.2f);
  cell[3] = 0;
  EXPECT_THROW(coarsened(m, cell), Error);
  cell[3] = std::nanf("");
  EXPECT_THROW(coarsened(m, cell), Error);
  cell[3] = 0.2f;
  m.positions[5].y = std::nanf("");  // no place in the blocks' order
  EXPECT_THROW(coarsened(m, cell), Error);
}

// A plane sampled 8 times more sparsely for x > 0 (jittered grids): the adaptive widths
// follow the spacing (support.hpp), the mesh's triangles follow them; a --cell asked for
// holds everywhere.
TEST(MeshCloud, TheTrianglesFollowTheSpacing) {
  PointCloud cloud;
  std::mt19937 random(7);
  std::uniform_real_distribution<float> jitter(-0.2f, 0.2f);
  for (const float step : {0.01f, 0.08f}) {
    const int n = int(std::lround(1.0f / step));
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < 2 * n; ++j) {
        const float x = (float(i) + 0.5f + jitter(random)) * step, y = -1 + (float(j) + 0.5f + jitter(random)) * step;
        cloud.positions.push_back(vec3(step < 0.05f ? -x : x, y, 0));
      }
  }
  const auto made = [&](float cell) {
    MeshParams params;
    params.projection = ProjectionParams::from_h(test::suggested_h(cloud));
    params.projection.support = Support::adaptive;
    params.cell = cell;
    Stats stats;
    return mesh_cloud(cloud, params, Backend::cpu, stats);
  };
  const auto fine = [](vec3 p) { return p.x < -0.3f && std::abs(p.y) < 0.7f; };
  const auto coarse = [](vec3 p) { return p.x > 0.3f && std::abs(p.y) < 0.7f; };
  const CloudMesh adapted = made(0);
  EXPECT_GT(mean_edge(adapted.mesh, coarse), 4 * mean_edge(adapted.mesh, fine));
  EXPECT_GT(adapted.counts.collapsed_vertices, 0);
  EXPECT_EQ(topology(adapted.mesh).components, 1);
  const CloudMesh asked = made(adapted.cell);
  EXPECT_LT(mean_edge(asked.mesh, coarse), 1.25 * mean_edge(asked.mesh, fine));
}

}  // namespace
}  // namespace pss
