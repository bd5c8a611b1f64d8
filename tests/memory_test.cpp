// The peak resident memory of each phase that --stats records (issue 28): a phase's own peak,
// not the process's so far; an outer phase's holds its inner phases'; the whole run's is
// "total"; every phase a command times has one; and without --stats nothing is watched.
// And the memory the process may take (physical_memory_bytes).
#include <gtest/gtest.h>

#include <sys/mman.h>
#include <sys/resource.h>

#include <algorithm>
#include <cstdint>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "pss/core/memory.hpp"
#include "pss/core/stats.hpp"
#include "support/cli.hpp"

namespace pss {
namespace {

constexpr std::int64_t kBlock = std::int64_t(128) << 20;

// Whether this system tells the peak resident size and lets it be reset (Linux 4.0): asked
// here, not of the code under test, so that a peak it fails to record fails the test.
bool peaks_are_told() {
  std::ofstream reset("/proc/self/clear_refs");
  reset << "5";
  reset.flush();
  return reset.good() && std::ifstream("/proc/self/status").good();
}

// Touches every page of kBlock bytes, so that they are resident, and gives them back: mapped
// and unmapped here, not through an allocator that may keep them (AddressSanitizer's
// quarantine does).
void touch_a_block() {
  void* mapped = ::mmap(nullptr, std::size_t(kBlock), PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  ASSERT_NE(mapped, MAP_FAILED);
  char* block = static_cast<char*>(mapped);
  for (std::size_t i = 0; i < std::size_t(kBlock); i += 4096) block[i] = char(i >> 12);
  ::munmap(mapped, std::size_t(kBlock));
}

// VmHWM, read here.
std::int64_t high_water_mark() {
  std::ifstream status("/proc/self/status");
  for (std::string line; std::getline(status, line);)
    if (line.rfind("VmHWM:", 0) == 0) return std::stoll(line.substr(6)) * 1024;
  return -1;
}

// /proc/meminfo's MemTotal, or the control group's memory.max where lower, read here.
TEST(PhysicalMemory, IsTheMachinesOrItsGroupsLimitWhereLower) {
  std::int64_t expected = -1;
  std::ifstream meminfo("/proc/meminfo");
  for (std::string line; std::getline(meminfo, line);)
    if (line.rfind("MemTotal:", 0) == 0) expected = std::stoll(line.substr(9)) * 1024;
  if (expected < 0) GTEST_SKIP() << "no /proc/meminfo";
  std::ifstream group("/sys/fs/cgroup/memory.max");
  std::string limit;
  if (group >> limit && limit != "max") expected = std::min(expected, std::int64_t(std::stoll(limit)));
  EXPECT_EQ(physical_memory_bytes(), expected);
}

TEST(PeakMemory, EachPhaseHasItsOwnPeakAndAnOuterPhaseHoldsItsInners) {
  if (!peaks_are_told()) GTEST_SKIP() << "this system neither tells nor resets the resident peak";
  watch_peak_memory(true);
  Stats stats;
  {
    ScopedPhase outer(stats, "outer", false);
    {
      ScopedPhase big(stats, "big", false);
      touch_a_block();
    }
    ScopedPhase small(stats, "small", false);
  }
  const nlohmann::json peak = stats.to_json()["peak_bytes"];
  for (const char* phase : {"big", "small", "outer", "total"}) ASSERT_TRUE(peak.contains(phase)) << phase;
  const std::int64_t big = peak["big"], small = peak["small"], outer = peak["outer"], total = peak["total"];
  EXPECT_GE(big, kBlock);
  EXPECT_LT(small, big - kBlock / 2);  // its own peak: the block was freed before it began
  EXPECT_GE(outer, big);
  EXPECT_GE(total, outer);
  // A phase run again keeps its larger peak.
  stats.add_peak("small", big);
  stats.add_peak("small", 1);
  EXPECT_EQ(stats.to_json()["peak_bytes"]["small"], big);
}

// Without --stats nothing is watched: no phase has a peak, and the process's own mark, which
// getrusage and /usr/bin/time read, is left as it is.
TEST(PeakMemory, UnwatchedPhasesRecordNoPeakAndLeaveTheProcesssMarkAlone) {
  if (!peaks_are_told()) GTEST_SKIP() << "this system neither tells nor resets the resident peak";
  watch_peak_memory(false);
  touch_a_block();
  Stats stats;
  {
    ScopedPhase phase(stats, "unwatched", false);
  }
  EXPECT_GE(high_water_mark(), kBlock);
  EXPECT_EQ(stats.to_json()["peak_bytes"], nlohmann::json::object());
}

class PeakMemoryCli : public test::CliTest {};

// `project`, `mesh` and `render` record a peak for every phase they time, none above the
// whole run's.
TEST_F(PeakMemoryCli, EveryTimedPhaseHasAPeakWithinTheRunsPeak) {
  if (!peaks_are_told()) GTEST_SKIP() << "this system neither tells nor resets the resident peak";
  const std::string bunny = std::string(PSS_SOURCE_DIR) + "/data/bun_zipper.ply";
  for (const std::string command : {"project", "mesh", "render"}) {
    const std::string stats_path = path(command + ".json");
    const std::string output = path(command + (command == "render" ? ".png --size 64x64" : ".ply"));
    const test::CliResult r =
        test::run_pss(command + " " + bunny + " -o " + output + " --progress never --stats " + stats_path);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    std::ifstream in(stats_path);
    const nlohmann::json j = nlohmann::json::parse(in);
    const nlohmann::json& peak = j["peak_bytes"];
    ASSERT_TRUE(peak.contains("total")) << command;
    const std::int64_t total = peak["total"];
    EXPECT_GT(total, 35947 * 12) << command;  // at least the points' positions
    for (const auto& [phase, seconds] : j["seconds"].items()) {
      ASSERT_TRUE(peak.contains(phase)) << command << ": " << phase;
      EXPECT_GT(peak[phase].get<std::int64_t>(), 0) << command << ": " << phase;
      EXPECT_LE(peak[phase].get<std::int64_t>(), total) << command << ": " << phase;
    }
  }
}

// Without --stats the process's own peak stays whole for getrusage and /usr/bin/time: a
// mesh of the bunny peaks at ~75 MB while meshing; a mark reset at each phase would tell
// the ~20 MB of its last.
TEST_F(PeakMemoryCli, WithoutStatsTheProcesssPeakIsItsWholeRuns) {
  if (!peaks_are_told()) GTEST_SKIP() << "this system neither tells nor resets the resident peak";
  const std::string bunny = std::string(PSS_SOURCE_DIR) + "/data/bun_zipper.ply";
  const test::CliResult plain = test::run_pss("mesh " + bunny + " -o " + path("plain.ply") + " --progress never");
  ASSERT_EQ(plain.exit_code, 0) << plain.err;
  rusage children{};
  ASSERT_EQ(::getrusage(RUSAGE_CHILDREN, &children), 0);
  const std::int64_t unwatched = std::int64_t(children.ru_maxrss) * 1024;
  const std::string stats_path = path("stats.json");
  const test::CliResult r = test::run_pss("mesh " + bunny + " -o " + path("watched.ply") +
                                          " --progress never --stats " + stats_path);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::ifstream in(stats_path);
  const std::int64_t total = nlohmann::json::parse(in)["peak_bytes"]["total"];
  EXPECT_GT(unwatched, total * 9 / 10);
}

}  // namespace
}  // namespace pss
