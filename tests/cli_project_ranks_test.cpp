// mpirun -np N pss project (issue 28): rank 0 reads and writes, every rank projects its share
// of the tiles, and the output is byte for byte one process's with the same tiles; a cloud
// that fits in core is tiled all the same for the ranks to share; what tiles do not do runs
// in core on rank 0; a failure on rank 0 is one line and lets the other ranks go.
#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <string>

#include <nlohmann/json.hpp>

#include "support/cli.hpp"
#include "support/file_bytes.hpp"
#include "support/output_readers.hpp"

namespace pss {
namespace {

using ProjectRanks = test::CliTest;
using test::ScratchFolder;

// `pss <args>` on `ranks` processes of mpirun on this machine (as root too, with more ranks
// than cores, and each free to run on every core: the ranks then share them), stopped after
// two minutes should a rank wait forever.
test::CliResult run_ranks(int ranks, const std::string& args) {
  return test::run_shell("OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 timeout 120 " +
                         std::string(PSS_MPIEXEC) + " --oversubscribe --bind-to none -np " + std::to_string(ranks) +
                         " " + std::string(PSS_CLI) + " " + args);
}

#define SKIP_WITHOUT_MPI() \
  if (!PSS_HAVE_MPI) GTEST_SKIP() << "pss is built without MPI"

TEST_F(ProjectRanks, TwoAndThreeRanksWriteOneProcesssBytesAndCountEachRanksPoints) {
  SKIP_WITHOUT_MPI();
  const std::string file = write("torus.xyz", test::torus_xyz(50000, false, 0));
  const ScratchFolder scratch(dir_ / "scratch");
  const test::CliResult one =
      test::run_pss("project " + file + " -o " + path("one.ply") + " --memory 7400K --stats " + path("one.json"));
  ASSERT_EQ(one.exit_code, 0) << one.err;
  const int threads = nlohmann::json::parse(read(path("one.json")))["threads"].get<int>();
  ASSERT_NE(one.out.find("; tile by tile: "), std::string::npos) << one.out;
  for (const int ranks : {2, 3}) {
    SCOPED_TRACE(ranks);
    const std::string out = path(std::to_string(ranks) + ".ply"), stats = path(std::to_string(ranks) + ".json");
    const test::CliResult r = run_ranks(ranks, "project " + file + " -o " + out + " --memory 7400K --stats " + stats);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("; " + std::to_string(ranks) + " ranks)"), std::string::npos) << r.out;
    EXPECT_EQ(read(out), read(path("one.ply"))) << "the ranks' output differs from one process's";
    const nlohmann::json v = nlohmann::json::parse(read(stats));
    EXPECT_EQ(v["ranks"], ranks);
    EXPECT_EQ(v["threads"], std::max(1, threads / ranks)) << "the ranks on a machine share its cores";
    const auto per_rank = v["points_per_rank"].get<std::vector<std::uint64_t>>();
    ASSERT_EQ(per_rank.size(), std::size_t(ranks));
    EXPECT_EQ(std::accumulate(per_rank.begin(), per_rank.end(), std::uint64_t(0)), v["points"].get<std::uint64_t>());
    for (const std::uint64_t points : per_rank) EXPECT_GT(points, v["points"].get<std::uint64_t>() / (2 * ranks));
    EXPECT_TRUE(scratch.empty()) << "the tiles' scratch files are left behind";
  }
}

TEST_F(ProjectRanks, ACloudThatFitsInCoreIsSharedInTilesWithTheInCorePoints) {
  SKIP_WITHOUT_MPI();
  const std::string file = write("torus.xyz", test::torus_xyz(50000, false, 0));
  const test::CliResult core = test::run_pss("project " + file + " -o " + path("core.ply") + " --stats " + path("core.json"));
  ASSERT_EQ(core.exit_code, 0) << core.err;
  const test::CliResult r = run_ranks(2, "project " + file + " -o " + path("ranks.ply") + " --stats " + path("ranks.json"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("; tile by tile: "), std::string::npos) << r.out;
  const nlohmann::json v = nlohmann::json::parse(read(path("ranks.json")));
  EXPECT_TRUE(v["memory"]["tiled"].get<bool>());
  EXPECT_GE(v["memory"]["points_per_tile"].get<std::uint64_t>(), 4096u);
  EXPECT_LE(v["memory"]["points_per_tile"].get<std::uint64_t>(), 50000u / 8 + 1);
  EXPECT_GT(v["points_per_rank"][1].get<std::uint64_t>(), 0u);
  const test::PlyColumns in_core = test::read_ply_columns(path("core.ply"));
  const test::PlyColumns ranks = test::read_ply_columns(path("ranks.ply"));
  ASSERT_EQ(ranks.columns.at("x").size(), in_core.columns.at("x").size());
  const nlohmann::json c = nlohmann::json::parse(read(path("core.json")));
  const test::ProjectedApart apart = test::compare_projected(ranks, in_core, 2 * c["params"]["t_tolerance"].get<double>());
  EXPECT_EQ(apart.apart, 0u);
  EXPECT_EQ(apart.facing_apart, 0u);
  EXPECT_LE(apart.status_differ, in_core.columns.at("x").size() / 200);
}

// A cloud sampled in rows (its adaptive widths are not tiled yet) runs in core on rank 0.
TEST_F(ProjectRanks, WhatTilesDoNotDoRunsInCoreOnRankZero) {
  SKIP_WITHOUT_MPI();
  std::string text;  // rows 2 apart, each sampled every 0.1
  for (int r = 0; r < 50; ++r)
    for (int s = 0; s < 400; ++s) text += std::to_string(0.1 * s) + " " + std::to_string(2.0 * r) + " 0\n";
  const std::string file = write("rows.xyz", text);
  ASSERT_EQ(test::run_pss("project " + file + " -o " + path("one.ply") + " --stats " + path("one.json")).exit_code, 0);
  const test::CliResult r = run_ranks(2, "project " + file + " -o " + path("ranks.ply") + " --stats " + path("s.json"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("; in core; 2 ranks)"), std::string::npos) << r.out;
  EXPECT_EQ(read(path("ranks.ply")), read(path("one.ply")));
  const nlohmann::json v = nlohmann::json::parse(read(path("s.json")));
  EXPECT_EQ(v["points_per_rank"], nlohmann::json::array({20000, 0}));
  EXPECT_EQ(v["threads"], nlohmann::json::parse(read(path("one.json")))["threads"])
      << "rank 0 alone takes all the machine's cores";
}

// A file's normals, their seams turned over the ranks' tiles: one process's bytes.
TEST_F(ProjectRanks, AFilesNormalsAreSharedByTheRanks) {
  SKIP_WITHOUT_MPI();
  const std::string file = write("torus.xyz", test::torus_xyz(20000, false, 1.0));
  ASSERT_EQ(test::run_pss("project " + file + " -o " + path("one.ply")).exit_code, 0);
  const test::CliResult r = run_ranks(2, "project " + file + " -o " + path("ranks.ply") + " --stats " + path("s.json"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("; tile by tile: "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("(the file's normals)"), std::string::npos) << r.out;
  EXPECT_EQ(read(path("ranks.ply")), read(path("one.ply")));
  const nlohmann::json v = nlohmann::json::parse(read(path("s.json")));
  EXPECT_GT(v["points_per_rank"][1].get<std::uint64_t>(), 0u);
}

// APSS and RIMLS under mpirun: the samples' normals' steps shared by the ranks too.
TEST_F(ProjectRanks, RimlsInTilesOverRanksIsOneProcesssBytes) {
  SKIP_WITHOUT_MPI();
  const std::string file = write("torus.xyz", test::torus_xyz(50000, false, 0));
  const ScratchFolder scratch(dir_ / "scratch");
  const test::CliResult one = test::run_pss("project " + file + " -o " + path("one.ply") + " --surface rimls --memory 7400K");
  ASSERT_EQ(one.exit_code, 0) << one.err;
  ASSERT_NE(one.out.find("; tile by tile: "), std::string::npos) << one.out;
  const test::CliResult r =
      run_ranks(3, "project " + file + " -o " + path("ranks.ply") + " --surface rimls --memory 7400K --stats " + path("s.json"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("; tile by tile: "), std::string::npos) << r.out;
  EXPECT_TRUE(read(path("ranks.ply")) == read(path("one.ply"))) << "the ranks' output differs from one process's";
  const auto per_rank = nlohmann::json::parse(read(path("s.json")))["points_per_rank"].get<std::vector<std::uint64_t>>();
  for (const std::uint64_t points : per_rank) EXPECT_GT(points, 0u);
  EXPECT_TRUE(scratch.empty());
}

TEST_F(ProjectRanks, AFailureOnRankZeroIsOneLineAndLetsTheOtherRanksGo) {
  SKIP_WITHOUT_MPI();
  const std::string file = write("torus.xyz", test::torus_xyz(20000, false, 0) + "1 2 oops\n");
  const test::CliResult r = run_ranks(3, "project " + file + " -o " + path("o.ply"));
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.exit_code, 124) << "a rank waited until the timeout";
  EXPECT_NE(r.err.find("pss: error: " + file), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("pss: error", r.err.find("pss: error") + 1), std::string::npos) << "one rank says it, once";
  EXPECT_FALSE(std::filesystem::exists(path("o.ply")));
}

// A rank killed while the tiles are worked on: mpirun ends the run, which fails, with no
// output and no scratch file left (rank 0 removes them on the SIGTERM mpirun sends it).
TEST_F(ProjectRanks, ARankThatDiesEndsTheRunWithNoOutputAndNoScratch) {
  SKIP_WITHOUT_MPI();
  const std::string file = write("torus.xyz", test::torus_xyz(50000, false, 0));
  const ScratchFolder scratch(dir_ / "scratch");
  const std::string err = path("err.txt"), pss = std::string(PSS_CLI) + " project " + file;
  // Rank 1 is the pss process whose environment says OMPI_COMM_WORLD_RANK=1.
  const std::string script =
      "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 timeout 120 " + std::string(PSS_MPIEXEC) +
      " --oversubscribe -np 2 " + pss + " -o " + path("o.ply") + " --memory 7400K --progress always 2>" + err +
      " & run=$!\n"
      "for i in $(seq 600); do grep -q projecting " + err + " && break; sleep 0.05; done\n"
      "for p in $(pgrep -f '" + pss + "'); do\n"
      "  tr '\\0' '\\n' </proc/$p/environ 2>/dev/null | grep -qx OMPI_COMM_WORLD_RANK=1 && kill -9 $p && echo killed\n"
      "done\n"
      "wait $run; echo exit=$?\n";
  const test::CliResult r = test::run_shell("bash " + write("kill.sh", script));
  EXPECT_NE(r.out.find("killed"), std::string::npos) << r.out << read(err);
  EXPECT_EQ(r.out.find("exit=0"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("exit=124"), std::string::npos) << "the run waited until the timeout";
  EXPECT_FALSE(std::filesystem::exists(path("o.ply")));
  EXPECT_TRUE(scratch.empty()) << "the tiles' scratch files are left behind";
}

// mpirun -np N pss mesh: the ranks share the tiles' pieces, and the mesh, whatever the tiles
// (tests/tiled_mesh_test.cpp), is byte for byte one process's with tiles of another size.
TEST_F(ProjectRanks, TheRanksMeshOneProcesssMeshInTilesOfAnotherSize) {
  SKIP_WITHOUT_MPI();
  const std::string file = write("torus.xyz", test::torus_xyz(60000, false, 0));
  const ScratchFolder scratch(dir_ / "scratch");
  const test::CliResult one = test::run_pss("mesh " + file + " -o " + path("one.ply") + " --memory 57M");
  ASSERT_EQ(one.exit_code, 0) << one.err;
  ASSERT_NE(one.out.find("tile by tile: "), std::string::npos) << one.out;
  const test::CliResult r = run_ranks(2, "mesh " + file + " -o " + path("two.ply") + " --stats " + path("two.json"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find(", 2 ranks)"), std::string::npos) << r.out;
  EXPECT_NE(one.out.substr(one.out.find("tile by tile"), 40), r.out.substr(r.out.find("tile by tile"), 40))
      << "the same tiles: the test would not tell seams apart";
  EXPECT_EQ(read(path("two.ply")), read(path("one.ply"))) << "the ranks' mesh differs from one process's";
  const test::CliResult three = run_ranks(3, "mesh " + file + " -o " + path("three.ply"));
  ASSERT_EQ(three.exit_code, 0) << three.err;
  EXPECT_EQ(read(path("three.ply")), read(path("one.ply"))) << "3 ranks' mesh differs from one process's";
  const nlohmann::json v = nlohmann::json::parse(read(path("two.json")));
  EXPECT_EQ(v["ranks"], 2);
  EXPECT_GT(v["points_per_rank"][1].get<std::uint64_t>(), 0u);
  EXPECT_TRUE(scratch.empty()) << "the tiles' scratch files are left behind";
}

}  // namespace
}  // namespace pss
