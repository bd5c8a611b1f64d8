// Outputs of the pss commands are all-or-nothing and never replace what they must not
// (issue 8): every destination is checked before any work, all are renamed into place only
// once all are written, a FIFO, symlink or the input itself is refused, and a SIGTERM
// during a run leaves no temporary behind.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>

#include "pss/io/ply.hpp"
#include "support/cli.hpp"
#include "support/shapes.hpp"

namespace pss {
namespace {

namespace fs = std::filesystem;

class CliOutputs : public testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("pss-cli-outputs-" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    test::SampleOptions o;
    o.count = 2000;
    write_ply(path("sphere.ply"), test::sample(test::Sphere{}, o));
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  std::string read(const std::string& name) const {
    std::ifstream in(path(name), std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
  }
  int temporaries() const {
    int n = 0;
    for (const auto& entry : fs::recursive_directory_iterator(dir_))
      n += entry.path().filename().string().find(".tmp-") != std::string::npos;
    return n;
  }
  // A refused run: non-zero exit, one line naming `name`, and no temporary left over.
  void expect_refused(const std::string& args, const std::string& name) {
    const test::CliResult r = test::run_pss(args);
    EXPECT_NE(r.exit_code, 0) << args;
    EXPECT_EQ(test::line_count(r.err), 1) << r.err;
    EXPECT_NE(r.err.find(name), std::string::npos) << r.err;
    EXPECT_EQ(temporaries(), 0);
  }
  fs::path dir_;
};

TEST_F(CliOutputs, HitsIntoADirectoryWritesNoImage) {
  fs::create_directories(path("hits"));
  expect_refused("render " + path("sphere.ply") + " --size 32x32 -o " + path("o.png") + " --hits " + path("hits"),
                 path("hits"));
  EXPECT_FALSE(fs::exists(path("o.png")));
  EXPECT_TRUE(fs::is_directory(path("hits")));
}

TEST_F(CliOutputs, StatsInAMissingDirectoryWritesNoPly) {
  expect_refused("project " + path("sphere.ply") + " -o " + path("p.ply") + " --stats " + path("missing/s.json"),
                 path("missing/s.json"));
  EXPECT_FALSE(fs::exists(path("p.ply")));
}

TEST_F(CliOutputs, AFifoIsRefusedAndStaysAFifo) {
  ASSERT_EQ(::mkfifo(path("fifo.ply").c_str(), 0600), 0);
  expect_refused("project " + path("sphere.ply") + " -o " + path("fifo.ply"), path("fifo.ply"));
  EXPECT_TRUE(fs::is_fifo(fs::symlink_status(path("fifo.ply"))));
}

TEST_F(CliOutputs, ASymlinkIsRefusedAndItsTargetKept) {
  std::ofstream(path("target.png")) << "keep";
  fs::create_symlink(path("target.png"), path("link.png"));
  expect_refused("render " + path("sphere.ply") + " --size 32x32 -o " + path("link.png"), path("link.png"));
  EXPECT_TRUE(fs::is_symlink(fs::symlink_status(path("link.png"))));
  EXPECT_EQ(read("target.png"), "keep");
}

TEST_F(CliOutputs, TheSameOutputTwiceIsRefused) {
  expect_refused("render " + path("sphere.ply") + " --size 32x32 -o " + path("o.png") + " --hits " + path("x.ply") +
                     " --stats " + path("x.ply"),
                 path("x.ply") + ": cannot write: named twice");
  EXPECT_FALSE(fs::exists(path("x.ply")));
  EXPECT_FALSE(fs::exists(path("o.png")));
  // Spelled differently, still the same file.
  expect_refused("project " + path("sphere.ply") + " -o " + path("p.ply") + " --stats " + dir_.string() +
                     "/../" + dir_.filename().string() + "/p.ply",
                 "p.ply");
  EXPECT_FALSE(fs::exists(path("p.ply")));
}

TEST_F(CliOutputs, TheInputAsOutputIsRefusedAndKept) {
  const std::string before = read("sphere.ply");
  expect_refused("project " + path("sphere.ply") + " -o " + path("sphere.ply"), path("sphere.ply"));
  expect_refused("render " + path("sphere.ply") + " --size 32x32 -o " + path("o.png") + " --stats " +
                     path("sphere.ply"),
                 path("sphere.ply"));
  EXPECT_EQ(read("sphere.ply"), before);
  EXPECT_FALSE(fs::exists(path("o.png")));
}

TEST_F(CliOutputs, AllOutputsAppearOnSuccess) {
  const test::CliResult r = test::run_pss("render " + path("sphere.ply") + " --size 32x32 -o " + path("o.png") +
                                          " --hits " + path("h.ply") + " --stats " + path("s.json"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::is_regular_file(path("o.png")));
  EXPECT_TRUE(fs::is_regular_file(path("h.ply")));
  EXPECT_TRUE(fs::is_regular_file(path("s.json")));
  EXPECT_EQ(temporaries(), 0);
}

// A long render killed by SIGTERM once its outputs' temporaries exist: they are removed,
// and pss still dies of the signal (its parent sees that, not an ordinary exit).
TEST_F(CliOutputs, SigtermRemovesTheTemporaries) {
  const std::string bunny = std::string(PSS_SOURCE_DIR) + "/data/bun_zipper.ply";
  const std::string out = path("o.png"), hits = path("h.ply");
  const pid_t pid = ::fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    std::freopen("/dev/null", "w", stdout);
    ::execl(PSS_CLI, PSS_CLI, "render", bunny.c_str(), "--size", "2048x2048", "-o", out.c_str(), "--hits",
            hits.c_str(), "--backend", "cpu", static_cast<char*>(nullptr));
    ::_exit(127);
  }
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  while (temporaries() < 2 && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  const int seen = temporaries();
  std::this_thread::sleep_for(std::chrono::milliseconds(300));  // well into the render
  ::kill(pid, SIGTERM);
  int status = 0;
  ASSERT_EQ(::waitpid(pid, &status, 0), pid);
  EXPECT_EQ(seen, 2) << "the outputs' temporaries should exist while rendering";
  ASSERT_TRUE(WIFSIGNALED(status)) << "exited with " << WEXITSTATUS(status) << " before the signal";
  EXPECT_EQ(WTERMSIG(status), SIGTERM);
  EXPECT_EQ(temporaries(), 0);
  EXPECT_FALSE(fs::exists(out));
  EXPECT_FALSE(fs::exists(hits));
}


// An image of the background alone, or an empty point file, is written but said to be so, as
// pss volume says of its images (a new user's trial: both were silent).
TEST_F(CliOutputs, NothingHitOrExtractedIsSaid) {
  const std::string bunny = std::string(PSS_SOURCE_DIR) + "/data/bun_zipper.ply";
  const test::CliResult away =
      test::run_pss("render " + bunny + " -o " + path("away.png") + " --size 32x32 --look-at 5,5,5 --distance 0.1");
  EXPECT_EQ(away.exit_code, 0) << away.err;
  EXPECT_TRUE(std::filesystem::exists(path("away.png")));
  EXPECT_NE(away.err.find("pss render: no ray hit the surface of " + bunny), std::string::npos) << away.err;
  const test::CliResult seen = test::run_pss("render " + bunny + " -o " + path("seen.png") + " --size 32x32");
  EXPECT_EQ(seen.err.find("no ray hit"), std::string::npos) << seen.err;
  {
    std::ofstream raw(path("const.raw"), std::ios::binary);
    const float seven = 7;
    for (int i = 0; i < 16 * 16 * 16; ++i) raw.write(reinterpret_cast<const char*>(&seven), sizeof seven);
  }
  const test::CliResult flat = test::run_pss("extract " + path("const.raw") +
                                             " --dims 16x16x16 --type float32 --iso 7 -o " + path("flat.ply"));
  EXPECT_EQ(flat.exit_code, 0) << flat.err;
  EXPECT_NE(flat.err.find("pss extract: no point of " + path("const.raw") + " lies on the surface"), std::string::npos)
      << flat.err;
}
}  // namespace
}  // namespace pss
