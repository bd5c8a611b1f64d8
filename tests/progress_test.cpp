// Progress on stderr (core/progress.hpp): lines a log can read, a bar on a terminal,
// nothing when off; and `--progress` on the CLI, whose summary times the whole run.
#include <fcntl.h>
#include <pty.h>
#include <sys/wait.h>
#include <unistd.h>

#include <regex>
#include <sstream>
#include <stdexcept>
#include <thread>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "pss/core/progress.hpp"
#include "pss/core/stats.hpp"
#include "support/cli.hpp"

namespace pss {
namespace {

// Sets a mode for one test and puts back the default.
struct ModeScope {
  explicit ModeScope(ProgressMode m) { set_progress_mode(m); }
  ~ModeScope() { set_progress_mode(ProgressMode::automatic); }
};

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

TEST(ProgressLines, OneLineAPhaseBeginsAndPerTenPerCentInOrderFromManyThreads) {
  const ModeScope mode(ProgressMode::always);
  testing::internal::CaptureStderr();
  {
    Progress progress("work", 1000);
    progress.advance(50);
    std::this_thread::sleep_for(std::chrono::milliseconds(1100));  // past the quiet first second
    std::vector<std::thread> threads;
    for (int t = 0; t < 4; ++t)
      threads.emplace_back([&] {
        for (int i = 0; i < 237; ++i) progress.advance(1);
      });
    for (auto& t : threads) t.join();
    progress.advance(2);
  }
  const std::vector<std::string> lines = lines_of(testing::internal::GetCapturedStderr());
  ASSERT_EQ(lines.size(), 11u);
  EXPECT_EQ(lines[0], "work: 1000 steps ...");
  for (int d = 1; d <= 9; ++d)
    EXPECT_TRUE(std::regex_match(lines[d], std::regex("work: " + std::to_string(10 * d) + "% after [0-9.]+ s.*")))
        << lines[d];
  EXPECT_TRUE(std::regex_match(lines[10], std::regex("work: done in [0-9.]+ s"))) << lines[10];
}

// Steps added as the work finds them (a mesh's band, wave by wave) stay one phase: one first
// line, one done line, and a 10 % line only where the grown total's share passes a new one.
TEST(ProgressLines, StepsAddedAsTheyAreFoundStayOnePhase) {
  const ModeScope mode(ProgressMode::always);
  testing::internal::CaptureStderr();
  {
    Progress progress("band", 10);
    std::this_thread::sleep_for(std::chrono::milliseconds(1100));
    progress.advance(5);   // 50 %
    progress.add_total(10);
    progress.advance(5);   // 10 of 20: 50 % again, not written twice
    progress.advance(4);   // 70 % of the grown total (140 % of the first)
  }
  const std::vector<std::string> lines = lines_of(testing::internal::GetCapturedStderr());
  ASSERT_EQ(lines.size(), 9u);
  EXPECT_EQ(lines[0], "band: 10 steps ...");
  EXPECT_EQ(lines[5].rfind("band: 50% after", 0), 0u) << lines[5];
  EXPECT_EQ(lines[6].rfind("band: 60% after", 0), 0u) << lines[6];
  EXPECT_EQ(lines[7].rfind("band: 70% after", 0), 0u) << lines[7];
  EXPECT_TRUE(std::regex_match(lines[8], std::regex("band: done in [0-9.]+ s"))) << lines[8];
}

TEST(ProgressLines, ALargeStepWritesEveryTenPerCentItCrosses) {
  const ModeScope mode(ProgressMode::always);
  testing::internal::CaptureStderr();
  {
    Progress progress("jump", 10);
    std::this_thread::sleep_for(std::chrono::milliseconds(1100));
    progress.advance(3);
    progress.advance(7);
  }
  const std::vector<std::string> lines = lines_of(testing::internal::GetCapturedStderr());
  ASSERT_EQ(lines.size(), 11u);
  EXPECT_EQ(lines[3].rfind("jump: 30% after", 0), 0u) << lines[3];
  EXPECT_EQ(lines[9].rfind("jump: 90% after", 0), 0u) << lines[9];
}

TEST(ProgressLines, APhaseShorterThanASecondWritesOnlyItsFirstAndLastLines) {
  const ModeScope mode(ProgressMode::always);
  testing::internal::CaptureStderr();
  {
    Progress progress("quick", 10);
    progress.advance(5);
    progress.advance(5);
  }
  const std::vector<std::string> lines = lines_of(testing::internal::GetCapturedStderr());
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_EQ(lines[0], "quick: 10 steps ...");
  EXPECT_EQ(lines[1].rfind("quick: done in", 0), 0u) << lines[1];
}

TEST(ProgressLines, TheTenPerCentsOfTheQuietFirstSecondAreNotWrittenLate) {
  const ModeScope mode(ProgressMode::always);
  testing::internal::CaptureStderr();
  {
    Progress progress("late", 10);
    progress.advance(4);
    std::this_thread::sleep_for(std::chrono::milliseconds(1100));
    progress.advance(1);
  }
  const std::vector<std::string> lines = lines_of(testing::internal::GetCapturedStderr());
  ASSERT_EQ(lines.size(), 3u);
  EXPECT_EQ(lines[1].rfind("late: 50% after 1.", 0), 0u) << lines[1];
}

TEST(ProgressLines, AnErrorThatUnwindsThePhaseIsNotCalledDone) {
  const ModeScope mode(ProgressMode::always);
  testing::internal::CaptureStderr();
  try {
    Progress progress("failing", 10);
    std::this_thread::sleep_for(std::chrono::milliseconds(1100));
    progress.advance(5);
    throw std::runtime_error("stop");
  } catch (const std::runtime_error&) {
  }
  const std::string err = testing::internal::GetCapturedStderr();
  EXPECT_NE(err.find("failing: 50% after"), std::string::npos) << err;
  EXPECT_EQ(err.find("done"), std::string::npos) << err;
}

TEST(ProgressLines, APhaseWithoutStepsSaysWhenItBeginsAndHowLongItTook) {
  const ModeScope mode(ProgressMode::always);
  Stats stats;
  testing::internal::CaptureStderr();
  { ScopedPhase phase(stats, "read"); }
  { ScopedPhase quiet(stats, "counted elsewhere", false); }
  const std::vector<std::string> lines = lines_of(testing::internal::GetCapturedStderr());
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_EQ(lines[0], "read ...");
  EXPECT_TRUE(std::regex_match(lines[1], std::regex("read: done in [0-9.]+ s"))) << lines[1];
}

TEST(ProgressLines, APhaseThatAnErrorEndsIsNotCalledDone) {
  const ModeScope mode(ProgressMode::always);
  Stats stats;
  testing::internal::CaptureStderr();
  try {
    ScopedPhase phase(stats, "read");
    throw std::runtime_error("truncated");
  } catch (const std::runtime_error&) {
  }
  EXPECT_EQ(testing::internal::GetCapturedStderr(), "read ...\n");
}

TEST(ProgressLines, NothingWhenNeverOrWhenAutomaticAndStderrIsNoTerminal) {
  for (ProgressMode m : {ProgressMode::never, ProgressMode::automatic}) {
    const ModeScope mode(m);
    Stats stats;
    testing::internal::CaptureStderr();
    {
      ScopedPhase phase(stats, "read");
      Progress progress("work", 10);
      progress.advance(10);
    }
    EXPECT_EQ(testing::internal::GetCapturedStderr(), "") << int(m);
  }
}

// stderr on a pseudo-terminal for the scope: what was written there is read().
class TerminalStderr {
 public:
  TerminalStderr() {
    if (openpty(&master_, &slave_, nullptr, nullptr, nullptr) != 0) return;
    saved_ = dup(STDERR_FILENO);
    dup2(slave_, STDERR_FILENO);
    fcntl(master_, F_SETFL, O_NONBLOCK);
  }
  ~TerminalStderr() {
    restore();
    if (master_ >= 0) close(master_);
  }
  bool ok() const { return master_ >= 0; }
  std::string read() {
    restore();
    std::string text;
    char buffer[4096];
    for (ssize_t n; (n = ::read(master_, buffer, sizeof buffer)) > 0;) text.append(buffer, std::size_t(n));
    return text;
  }

 private:
  void restore() {
    if (saved_ < 0) return;
    std::fflush(stderr);
    dup2(saved_, STDERR_FILENO);
    close(saved_);
    close(slave_);
    saved_ = -1;
  }
  int master_ = -1, slave_ = -1, saved_ = -1;
};

TEST(ProgressBar, OnATerminalABarWithTheTimeLeftAndPhasesThatEraseThemselves) {
  for (ProgressMode m : {ProgressMode::automatic, ProgressMode::always}) {
    const ModeScope mode(m);
    TerminalStderr terminal;
    if (!terminal.ok()) GTEST_SKIP() << "no pseudo-terminal here";
    Stats stats;
    {
      ScopedPhase phase(stats, "orienting");
      Progress progress("rays", 100);
      for (int i = 0; i < 50; ++i) {
        progress.advance(1);
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
      }
      progress.advance(50);
    }
    const std::string out = terminal.read();
    EXPECT_NE(out.find("\rorienting ...\033[K"), std::string::npos) << out;
    EXPECT_TRUE(std::regex_search(out, std::regex("\rrays +\\[#+ +\\] +[0-9.]+%  [0-9.]+ s, [0-9.]+ s left")))
        << out;
    EXPECT_NE(out.find("[##############################] 100.0%"), std::string::npos) << out;
    EXPECT_EQ(out.find("done in"), std::string::npos) << out;  // log lines are for logs
  }
}

class ProgressCli : public test::CliTest {};

TEST_F(ProgressCli, AlwaysWritesEveryPhaseOfAProjectionIncludingTheOrientationAndTheSummaryTimesTheWholeRun) {
  const std::string cloud = PSS_SOURCE_DIR "/data/bun_zipper.ply";  // no normals: they are oriented
  const test::CliResult r =
      test::run_pss("project " + cloud + " -o " + path("p.ply") + " --stats " + path("p.json") + " --progress always");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // RIMLS, the default, orients its samples' normals (7 set aside), then projects.
  for (const char* line : {"read ...", "read: done in", "estimate h ...", "spatial index ...", "sample normals: done in",
                           "orient normals: 35940 steps ...", "orient normals: done in", "projecting: 35947 steps",
                           "projecting: done in", "write: done in"})
    EXPECT_NE(r.err.find(line), std::string::npos) << line << "\n" << r.err;
  EXPECT_EQ(r.err.find("\r"), std::string::npos) << "no bar off a terminal";

  const nlohmann::json stats = nlohmann::json::parse(read(path("p.json")));
  const auto& s = stats["seconds"];
  std::smatch m;
  ASSERT_TRUE(std::regex_search(r.out, m, std::regex("onto the PSS in ([0-9.]+) s"))) << r.out;
  EXPECT_NEAR(std::stod(m[1]), s["total"].get<double>(), 6e-4);
  EXPECT_GE(s["total"].get<double>(), s["read"].get<double>() + s["projection"].get<double>() +
                                          s["sample normals"].get<double>() + s["orient normals"].get<double>() +
                                          s["write"].get<double>());
}

// A mesh's band grows in waves, each a batch of corners: one phase for all of them (a new
// user's trial read nine "mesh corners" phases on the bunny).
TEST_F(ProgressCli, AMeshsBandIsOnePhaseOfCornersBeforeItsVertices) {
  const std::string cloud = PSS_SOURCE_DIR "/data/bun_zipper.ply";
  const test::CliResult r = test::run_pss("mesh " + cloud + " -o " + path("m.ply") + " --progress always");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::vector<std::string> lines = lines_of(r.err);
  int begun = 0, done = 0;
  std::size_t done_at = 0, vertices_at = 0;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    begun += std::regex_match(lines[i], std::regex("mesh corners: [0-9]+ steps \\.\\.\\."));
    if (lines[i].rfind("mesh corners: done in", 0) == 0) {
      ++done;
      done_at = i;
    }
    if (lines[i].rfind("mesh vertices: ", 0) == 0 && vertices_at == 0) vertices_at = i;
  }
  EXPECT_EQ(begun, 1) << r.err;
  EXPECT_EQ(done, 1) << r.err;
  EXPECT_LT(done_at, vertices_at) << r.err;
}

TEST_F(ProgressCli, NeverAndTheDefaultOffATerminalWriteNothingToStderr) {
  const std::string cloud = PSS_SOURCE_DIR "/data/bun_zipper.ply";
  for (const char* flag : {" --progress never", ""}) {
    const test::CliResult r = test::run_pss("project " + cloud + " -o " + path("p.ply") + flag);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(r.err, "") << flag;
  }
  expect_clean_failure("project " + cloud + " -o " + path("q.ply") + " --progress sometimes", "--progress",
                       path("q.ply"));
}

// What `pss ARGS` writes to stderr when stderr is a terminal (a pseudo-terminal), stdout
// discarded; empty when no pseudo-terminal can be opened.
std::string stderr_on_a_terminal(const std::vector<std::string>& args) {
  int master = -1, slave = -1;
  if (openpty(&master, &slave, nullptr, nullptr, nullptr) != 0) return {};
  const pid_t child = fork();
  if (child == 0) {
    dup2(slave, STDERR_FILENO);
    const int null = open("/dev/null", O_WRONLY);
    dup2(null, STDOUT_FILENO);
    std::vector<char*> argv{const_cast<char*>(PSS_CLI)};
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    execv(PSS_CLI, argv.data());
    _exit(127);
  }
  close(slave);
  std::string text;
  char buffer[4096];
  for (ssize_t n; (n = ::read(master, buffer, sizeof buffer)) > 0;) text.append(buffer, std::size_t(n));  // EIO at the end
  int status = 0;
  waitpid(child, &status, 0);
  close(master);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << text;
  return text;
}

TEST_F(ProgressCli, OnATerminalTheDefaultDrawsABarAndNeverDrawsNothing) {
  const std::string cloud = PSS_SOURCE_DIR "/data/bun_zipper.ply";
  const std::string bar = stderr_on_a_terminal({"project", cloud, "-o", path("p.ply")});
  if (bar.empty()) GTEST_SKIP() << "no pseudo-terminal here";
  EXPECT_NE(bar.find("\r"), std::string::npos) << bar;
  EXPECT_NE(bar.find("projecting"), std::string::npos) << bar;
  EXPECT_EQ(stderr_on_a_terminal({"project", cloud, "-o", path("p.ply"), "--progress", "never"}), "");
}

}  // namespace
}  // namespace pss
