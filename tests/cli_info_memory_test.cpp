// pss info --memory (issue 28): a cloud that needs more than the budget is read into tiles
// in $TMPDIR and gives the figures it gives in core, line for line; the tiles' scratch file
// goes with the run; budgets too small or not sizes are refused with one line.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <sys/wait.h>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "support/cli.hpp"
#include "support/file_bytes.hpp"

namespace pss {
namespace {

using InfoMemory = test::CliTest;
using test::ScratchFolder;

// The lines of `text` but those starting with one of `except`.
std::vector<std::string> lines_but(const std::string& text, std::initializer_list<std::string> except) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    bool keep = true;
    for (const std::string& prefix : except) keep = keep && line.rfind(prefix, 0) != 0;
    if (keep) out.push_back(line);
  }
  return out;
}

// About 34,000 points of a torus with normals, sparser on one side: 3.1 MiB in core.
TEST_F(InfoMemory, ACloudLargerThanTheBudgetGivesTheInCoreFiguresTileByTile) {
  const std::string file = write("torus.xyz", test::torus_xyz(60000, true, 1.0));
  const test::CliResult in_core = test::run_pss("info " + file);
  ASSERT_EQ(in_core.exit_code, 0) << in_core.err;
  EXPECT_NE(in_core.out.find("memory          in core"), std::string::npos) << in_core.out;
  const ScratchFolder scratch(dir_ / "scratch");
  const test::CliResult tiled = test::run_pss("info " + file + " --memory 3M --progress always");
  ASSERT_EQ(tiled.exit_code, 0) << tiled.err;
  // Each long phase tells a log when it is done.
  for (const char* phase : {"reading into tiles: done", "spacing: done", "support widths: done"})
    EXPECT_NE(tiled.err.find(phase), std::string::npos) << tiled.err;
  int tiles = 0;
  unsigned long long mean = 0, points = 0;
  const std::size_t at = tiled.out.find("memory          tile by tile: ");
  ASSERT_NE(at, std::string::npos) << tiled.out;
  ASSERT_EQ(std::sscanf(tiled.out.c_str() + at, "memory          tile by tile: %d tiles of about %llu points", &tiles,
                        &mean),
            2);
  EXPECT_GT(tiles, 4);
  const std::size_t count = in_core.out.find("points          ");
  ASSERT_NE(count, std::string::npos) << in_core.out;
  ASSERT_EQ(std::sscanf(in_core.out.c_str() + count, "points          %llu", &points), 1);
  EXPECT_NEAR(double(tiles) * double(mean), double(points), tiles / 2.0) << "the tiles' mean, not a tile's cap";
  EXPECT_EQ(lines_but(tiled.out, {"memory", "normals"}), lines_but(in_core.out, {"memory", "normals"}));
  EXPECT_NE(tiled.out.find("adaptive h_i    from "), std::string::npos) << tiled.out;
  EXPECT_NE(tiled.out.find("(with normals)"), std::string::npos) << tiled.out;
  EXPECT_NE(tiled.out.find("normals         the file's (whether they agree"), std::string::npos) << tiled.out;
  EXPECT_TRUE(scratch.empty()) << "the tiles' scratch file is left behind";
}

// Rows 2 apart, each sampled every 0.1: in core the rows' gaps widen the widths; tile by tile
// the widths are not given, and say why.
TEST_F(InfoMemory, ACloudOfRowsTileByTileSaysWhyItsWidthsAreNotGiven) {
  std::string text;
  for (int r = 0; r < 100; ++r)
    for (int s = 0; s < 400; ++s) text += std::to_string(0.1 * s) + " " + std::to_string(2.0 * r) + " 0\n";
  const std::string file = write("rows.xyz", text);
  const ScratchFolder scratch(dir_ / "scratch");
  const test::CliResult tiled = test::run_pss("info " + file + " --memory 3M");
  ASSERT_EQ(tiled.exit_code, 0) << tiled.err;
  EXPECT_NE(tiled.out.find("adaptive h_i    not given: the cloud is sampled in rows"), std::string::npos) << tiled.out;
  EXPECT_NE(tiled.out.find("suggested h"), std::string::npos) << tiled.out;
  EXPECT_TRUE(scratch.empty());
}

TEST_F(InfoMemory, BudgetsThatAreNoSizeOrTooSmallAreRefused) {
  const std::string file = write("torus.xyz", test::torus_xyz(60000, true, 0));
  for (const char* bad : {"2x", "nan", "-5M", "1K", "inf", "M", "3MM", "1e300G"}) {
    SCOPED_TRACE(bad);
    const test::CliResult r = test::run_pss("info " + file + " --memory " + bad);
    EXPECT_NE(r.exit_code, 0);
    EXPECT_EQ(test::line_count(r.err), 1) << r.err;
    EXPECT_NE(r.err.find("--memory"), std::string::npos) << r.err;
    EXPECT_TRUE(r.out.empty()) << r.out;
  }
  const test::CliResult small = test::run_pss("info " + file + " --memory 1M");
  EXPECT_NE(small.exit_code, 0);
  EXPECT_EQ(test::line_count(small.err), 1) << small.err;
  EXPECT_NE(small.err.find("--memory 1 MiB is too small for " + file), std::string::npos) << small.err;
  EXPECT_TRUE(small.out.empty()) << small.out;
  // The least budget it names is enough, and a KiB less is not (the tiles' buffer grows with
  // the budget: the least is what holds the rest beside it).
  unsigned long long least = 0;
  const std::size_t named = small.err.find("(--memory ");
  ASSERT_NE(named, std::string::npos) << small.err;
  ASSERT_EQ(std::sscanf(small.err.c_str() + named, "(--memory %lluK)", &least), 1) << small.err;
  EXPECT_EQ(test::run_pss("info " + file + " --memory " + std::to_string(least) + "K").exit_code, 0);
  const test::CliResult less = test::run_pss("info " + file + " --memory " + std::to_string(least - 1) + "K");
  EXPECT_NE(less.exit_code, 0);
  EXPECT_NE(less.err.find("(--memory " + std::to_string(least) + "K)"), std::string::npos) << less.err;
  // Sizes in every unit read the same: 4096K, 4M and 4MiB are one budget.
  for (const char* same : {"4096K", "4M", "4MiB", "4mb", "0.00390625G"}) {
    SCOPED_TRACE(same);
    const test::CliResult r = test::run_pss("info " + file + " --memory " + same);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("--memory 4 MiB)"), std::string::npos) << r.out;
  }
}

// A temporary folder that is none, and a disk that fills (a file-size limit): one line, no
// figures, and no scratch file left; an empty TMPDIR is /tmp.
TEST_F(InfoMemory, NoScratchFolderOrAFullDiskIsOneLineAndLeavesNothing) {
  const std::string file = write("torus.xyz", test::torus_xyz(60000, true, 0));
  const std::string out = path("out.txt"), err = path("err.txt");
  // pss run through the shell with `before` ahead of it: its exit status, or -1 if a signal
  // ended it.
  const auto run = [&](const std::string& before) {
    const int status = std::system((before + std::string(PSS_CLI) + " info " + file + " --memory 3M >" + out +
                                    " 2>" + err).c_str());
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  };
  EXPECT_EQ(run("TMPDIR=" + (dir_ / "none").string() + " "), 1);
  EXPECT_EQ(test::line_count(read(err)), 1) << read(err);
  EXPECT_NE(read(err).find("the temporary folder '" + (dir_ / "none").string() + "'"), std::string::npos) << read(err);
  EXPECT_TRUE(read(out).empty()) << read(out);
  // An empty TMPDIR is as none set: /tmp.
  EXPECT_EQ(run("TMPDIR= "), 0) << read(err);
  EXPECT_NE(read(out).find("memory          tile by tile"), std::string::npos) << read(out);

  const ScratchFolder scratch(dir_ / "scratch");
  // 256 KiB at most a file (the tiles' store needs 1 MiB): writing past it fails, an error
  // and not the signal that would kill pss and leave the file.
  EXPECT_EQ(run("ulimit -f 256; "), 1);
  const std::string message = read(err);
  EXPECT_EQ(test::line_count(message), 1) << message;
  EXPECT_NE(message.find("File too large"), std::string::npos) << message;
  EXPECT_TRUE(read(out).empty());
  EXPECT_TRUE(scratch.empty()) << "the scratch file is left behind";
}

}  // namespace
}  // namespace pss
