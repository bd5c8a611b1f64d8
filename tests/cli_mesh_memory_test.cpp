// pss mesh --memory (issue 28): a cloud that needs more than the budget is meshed tile by
// tile, the pieces welded at the seams into the in-core mesh, byte for byte; what the
// tiles do not do yet is refused in one line, and a run that fails leaves no output and no
// scratch.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include <nlohmann/json.hpp>

#include "pss/mesh/triangle_mesh.hpp"
#include "support/cli.hpp"
#include "support/file_bytes.hpp"
#include "support/mesh_checks.hpp"
#include "support/mesh_readers.hpp"

namespace pss {
namespace {

using MeshMemory = test::CliTest;
using test::ScratchFolder;

TEST_F(MeshMemory, TileByTileTheInCoreMeshsBytes) {
  const std::string file = write("torus.xyz", test::torus_xyz(60000, false, 0));
  const test::CliResult in_core = test::run_pss("mesh " + file + " -o " + path("core.ply"));
  ASSERT_EQ(in_core.exit_code, 0) << in_core.err;
  const ScratchFolder scratch(dir_ / "scratch");
  const test::CliResult tiled = test::run_pss("mesh " + file + " -o " + path("tiled.ply") + " --memory 57M --stats " +
                                              path("tiled.json") + " --progress always");
  ASSERT_EQ(tiled.exit_code, 0) << tiled.err;
  EXPECT_TRUE(scratch.empty()) << "the tiles' scratch files are left behind";
  EXPECT_NE(tiled.out.find("60000 points, tile by tile: "), std::string::npos) << tiled.out;
  EXPECT_NE(tiled.err.find("meshing tiles: done"), std::string::npos) << tiled.err;
  const nlohmann::json v = nlohmann::json::parse(read(path("tiled.json")));
  EXPECT_TRUE(v["memory"]["tiled"].get<bool>());
  EXPECT_EQ(v["points_per_rank"][0], 60000);
  const TriangleMesh mesh = test::read_mesh(path("tiled.ply"));
  test::expect_one_closed_surface(mesh, 0);
  EXPECT_EQ(read(path("tiled.ply")), read(path("core.ply"))) << "the tiles' mesh differs from the in-core mesh";
  double worst = 0;  // the file's torus, R = 1 and r = 0.35 about (596700, 4000000, 0)
  for (const vec3& q : mesh.positions) {
    const glm::dvec3 p = glm::dvec3(q) + mesh.origin - glm::dvec3(596700, 4000000, 0);
    worst = std::max(worst, std::abs(std::hypot(std::hypot(p.x, p.y) - 1, p.z) - 0.35));
  }
  EXPECT_LT(worst, 1e-3);
}

// A file's normals tile by tile: the in-core mesh's bytes, and the summary says whose normals.
TEST_F(MeshMemory, TheFilesNormalsAreTakenTileByTile) {
  const std::string file = write("torus.xyz", test::torus_xyz(60000, false, 1));
  const ScratchFolder scratch(dir_ / "scratch");
  ASSERT_EQ(test::run_pss("mesh " + file + " -o " + path("core.ply")).exit_code, 0);
  const test::CliResult r = test::run_pss("mesh " + file + " -o " + path("m.ply") + " --memory 57M");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("tile by tile"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("(the file's normals)"), std::string::npos) << r.out;
  EXPECT_EQ(read(path("m.ply")), read(path("core.ply")));
  EXPECT_TRUE(scratch.empty());
}

TEST_F(MeshMemory, AVolumeTakesNoMemoryFlag) {
  const std::string file = write("v.raw", std::string(8 * 8 * 8, '\x10'));
  expect_clean_failure("mesh " + file + " -o " + path("m.ply") + " --dims 8x8x8 --type uint8 --iso 10 --memory 1G",
                       "--memory", path("m.ply"));
}

}  // namespace
}  // namespace pss
