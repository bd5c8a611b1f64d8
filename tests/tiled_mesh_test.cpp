// pss mesh tile by tile (include/pss/tiles/mesh.hpp, issue 28): each tile marches the cubes
// whose centres lie in it, and the pieces weld at the seams by their vertices' keys into the
// one mesh whatever the tiles: the in-core mesh to the last bit (both in the cloud's unit
// frame, from the same samples), closed where the surface is, with its creases.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "pss/core/error.hpp"
#include "pss/io/point_cloud_file.hpp"
#include "pss/tiles/memory_plan.hpp"
#include "pss/tiles/mesh.hpp"
#include "support/cli.hpp"
#include "support/file_bytes.hpp"
#include "support/mesh_checks.hpp"
#include "support/render_truth.hpp"
#include "support/shapes.hpp"

namespace pss {
namespace {

using TiledMeshTest = test::CliTest;

MeshParams mesh_params(const std::string& file, SurfaceOperator surface) {
  MeshParams params;
  params.projection = ProjectionParams::from_h(test::suggested_h(read_point_cloud(file)));
  params.projection.support = Support::adaptive;
  params.projection.surface = surface;
  params.projection.borders = BorderMode::extend;
  return params;
}

// The file's mesh in tiles of about `per_tile` points, and how many tiles there were.
std::pair<TiledCloudMesh, int> mesh_tiled(const std::string& file, const std::filesystem::path& dir,
                                          const MeshParams& params, std::uint64_t per_tile) {
  Stats stats;
  const TiledCloud tiles(file, dir, per_tile, 1 << 16);
  return {mesh_in_tiles(tiles, params, Backend::cpu, dir, 4096, 1 << 16, stats), tiles.tiles()};
}

void expect_same_mesh(const TriangleMesh& a, const TriangleMesh& b) {
  ASSERT_EQ(a.positions.size(), b.positions.size());
  ASSERT_EQ(a.triangles.size(), b.triangles.size());
  std::size_t moved = 0, turned = 0, rewound = 0;
  for (std::size_t v = 0; v < a.positions.size(); ++v) {
    moved += a.positions[v] != b.positions[v];
    turned += a.normals[v] != b.normals[v];
  }
  for (std::size_t t = 0; t < a.triangles.size(); ++t) rewound += a.triangles[t] != b.triangles[t];
  EXPECT_EQ(moved, 0u);
  EXPECT_EQ(turned, 0u);
  EXPECT_EQ(rewound, 0u);
  EXPECT_EQ(a.origin, b.origin);
}

// A box with a bore: creases at every edge and rim, cut by the tiles' seams.
TEST_F(TiledMeshTest, TilesOfAnySizeWeldIntoTheInCoreMeshWithItsCreases) {
  const PointCloud box = test::sample(test::BoredBox{}, 0.04f);
  const std::string file = write("box.xyz", test::xyz_text(box.positions));
  const MeshParams params = mesh_params(file, SurfaceOperator::rimls);
  Stats stats;
  const CloudMesh in_core = mesh_cloud(read_point_cloud(file), params, Backend::cpu, stats);
  test::expect_one_closed_surface(in_core.mesh, 0);
  EXPECT_GT(in_core.counts.crease_vertices, 0);
  for (const std::uint64_t per_tile : {600u, 2500u}) {
    SCOPED_TRACE(per_tile);
    const auto [tiled, tiles] = mesh_tiled(file, dir_, params, per_tile);
    EXPECT_GE(tiles, per_tile == 600 ? 8 : 2);
    expect_same_mesh(tiled.mesh.mesh, in_core.mesh);
    EXPECT_EQ(tiled.mesh.counts.crease_vertices, in_core.counts.crease_vertices);
    EXPECT_EQ(tiled.mesh.counts.cubes_crossed, in_core.counts.cubes_crossed);
    EXPECT_EQ(tiled.mesh.counts.collapsed_vertices, in_core.counts.collapsed_vertices);
    EXPECT_GT(tiled.mesh.counts.corners, in_core.counts.corners) << "the tiles' margins are marched twice";
  }
}

// The georeferenced torus of torus_xyz (R = 1, r = 0.35 about (596700, 4000000, 0)): in tiles,
// the in-core mesh: one watertight surface of genus one on the torus.
TEST_F(TiledMeshTest, ATorusInTilesIsTheInCoreMesh) {
  const std::string file = write("torus.xyz", test::torus_xyz(20000, false, 0));
  const MeshParams params = mesh_params(file, SurfaceOperator::rimls);
  Stats stats;
  const CloudMesh in_core = mesh_cloud(read_point_cloud(file), params, Backend::cpu, stats);
  const auto [tiled, tiles] = mesh_tiled(file, dir_, params, 3000);
  EXPECT_GE(tiles, 6);
  const CloudMesh& m = tiled.mesh;
  test::expect_one_closed_surface(m.mesh, 0);
  expect_same_mesh(m.mesh, in_core.mesh);
  EXPECT_EQ(m.counts.cubes_crossed, in_core.counts.cubes_crossed);
  EXPECT_EQ(m.counts.collapsed_vertices, in_core.counts.collapsed_vertices);
  double worst = 0;
  for (std::size_t v = 0; v < m.mesh.positions.size(); ++v) {
    const glm::dvec3 p = glm::dvec3(m.mesh.positions[v]) + m.mesh.origin - glm::dvec3(596700, 4000000, 0);
    const double ring = std::hypot(p.x, p.y) - 1;
    worst = std::max(worst, std::abs(std::hypot(ring, p.z) - 0.35));
  }
  EXPECT_LT(worst, 0.05 * params.projection.h) << "a vertex off the torus";
  EXPECT_EQ(tiled.points_per_rank.size(), 1u);
  EXPECT_EQ(tiled.points_per_rank[0], 20000u);
}

// A sheet with a ball above it: the tiles over the sheet, away from the ball, lie within the
// halo of the sheet's tiles but hold no sample in their own (at 10⁶ points some of a torus's
// tiles did, and their empty work was refused); they give no piece, and the mesh is the
// in-core one.
TEST_F(TiledMeshTest, ATileNearTheSurfaceWithNoSampleInItsHaloGivesNoPiece) {
  const PointCloud cloud = test::sheet_and_ball(12000, test::Sphere{vec3(0.5f, 0.5f, 2.5f), 0.3f}, 1000);
  const std::string file = write("sheet.xyz", test::xyz_text(cloud.positions));
  const MeshParams params = mesh_params(file, SurfaceOperator::rimls);
  Stats stats;
  const CloudMesh in_core = mesh_cloud(read_point_cloud(file), params, Backend::cpu, stats);
  const auto [tiled, tiles] = mesh_tiled(file, dir_, params, 2000);
  EXPECT_GE(tiles, 12) << tiles;
  expect_same_mesh(tiled.mesh.mesh, in_core.mesh);
}

// A CAD part's exact normals in its file, those beyond x = 0.3 flipped: the seams' turn over
// the tiles mends them as in core, and the pieces weld, creases across the seams, into the
// in-core mesh.
TEST_F(TiledMeshTest, AFilesNormalsMeshInTilesAsInCore) {
  const PointCloud box = test::sample(test::BoredBox{}, 0.04f);
  std::string text;
  char line[200];
  for (std::size_t i = 0; i < box.positions.size(); ++i) {
    const vec3 p = box.positions[i], n = p.x > 0.3f ? -box.normals[i] : box.normals[i];
    std::snprintf(line, sizeof line, "%.9g %.9g %.9g %.9g %.9g %.9g\n", double(p.x), double(p.y), double(p.z),
                  double(n.x), double(n.y), double(n.z));
    text += line;
  }
  const std::string file = write("box.xyz", text);
  MeshParams params = mesh_params(file, SurfaceOperator::rimls);
  params.projection.normals = NormalSource::file;
  Stats stats;
  const CloudMesh in_core = mesh_cloud(read_point_cloud(file), params, Backend::cpu, stats);
  ASSERT_EQ(in_core.normals, NormalsUsed::file);
  EXPECT_GT(in_core.normals_turned, 1000u);
  test::expect_one_closed_surface(in_core.mesh, 0);
  const auto [tiled, tiles] = mesh_tiled(file, dir_, params, 1500);
  EXPECT_GE(tiles, 4);
  EXPECT_EQ(tiled.mesh.normals, NormalsUsed::file);
  EXPECT_EQ(tiled.mesh.normals_turned, in_core.normals_turned);
  expect_same_mesh(tiled.mesh.mesh, in_core.mesh);
  EXPECT_EQ(tiled.mesh.counts.crease_vertices, in_core.counts.crease_vertices);
}

}  // namespace
}  // namespace pss
