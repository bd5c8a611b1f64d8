// The results that come back before their turn (tiles/waiting_results.hpp): kept in a scratch
// file, not in memory, and given back whole, in any order, once each.
#include <gtest/gtest.h>

#include <cstddef>
#include <filesystem>
#include <string>
#include <tuple>
#include <vector>

#include "pss/core/error.hpp"
#include "pss/tiles/waiting_results.hpp"
#include "support/cli.hpp"

namespace pss {
namespace {

namespace fs = std::filesystem;

std::vector<std::byte> bytes(std::size_t count, int seed) {
  std::vector<std::byte> out(count);
  for (std::size_t i = 0; i < count; ++i) out[i] = std::byte((i * 31 + std::size_t(seed) * 7) & 0xff);
  return out;
}

std::vector<fs::path> files_in(const fs::path& folder) {
  std::vector<fs::path> out;
  for (const auto& entry : fs::directory_iterator(folder)) out.push_back(entry.path());
  return out;
}

TEST(WaitingResults, GivesEachResultAndItsNotesBackWholeInTheOrderAsked) {
  const test::TestFolder folder;
  WaitingResults waiting(folder.path());
  // Tiles 4, 2 and 3 come back before tile 1, each of a size of its own, one without notes.
  waiting.put(4, 2, bytes(1000, 4), bytes(40, 40));
  waiting.put(2, 1, bytes(3, 2), {});
  waiting.put(3, 0, bytes(70000, 3), bytes(9, 30));
  EXPECT_EQ(waiting.size(), 3u);
  EXPECT_FALSE(waiting.holds(1));
  EXPECT_TRUE(waiting.holds(3));
  for (const auto& [place, rank, size, notes, seed] :
       {std::tuple{2, 1, 3, 0, 2}, std::tuple{3, 0, 70000, 9, 3}, std::tuple{4, 2, 1000, 40, 4}}) {
    SCOPED_TRACE(place);
    const WaitingResults::Taken t = waiting.take(std::size_t(place));
    EXPECT_EQ(t.rank, rank);
    EXPECT_EQ(t.result, bytes(std::size_t(size), seed));
    EXPECT_EQ(t.notes, bytes(std::size_t(notes), seed * 10));
    EXPECT_FALSE(waiting.holds(std::size_t(place)));
  }
  EXPECT_EQ(waiting.size(), 0u);
  EXPECT_THROW(waiting.take(4), Error);  // once each
}

// Not in memory: in one scratch file of the folder, made at the first result that waits and
// removed at the end; once none waits, the next is written over what was read, so that the
// file is as large as the most results waiting at once, not as all that ever waited.
TEST(WaitingResults, WaitInOneScratchFileNoLargerThanTheMostWaitingAtOnce) {
  const test::TestFolder folder;
  {
    WaitingResults waiting(folder.path());
    EXPECT_TRUE(files_in(folder.path()).empty());
    for (std::size_t round = 0; round < 5; ++round) {
      waiting.put(2 * round + 1, 1, bytes(5000, int(round)), bytes(100, int(round)));
      waiting.put(2 * round, 1, bytes(5000, int(round) + 1), bytes(100, int(round) + 1));
      ASSERT_EQ(files_in(folder.path()).size(), 1u);
      EXPECT_LE(fs::file_size(files_in(folder.path())[0]), 2u * 5100u) << "round " << round;
      EXPECT_EQ(waiting.take(2 * round).result, bytes(5000, int(round) + 1));
      EXPECT_EQ(waiting.take(2 * round + 1).result, bytes(5000, int(round)));
    }
  }
  EXPECT_TRUE(files_in(folder.path()).empty());
}

// The scratch folder is needed only once a result waits; one that cannot take the file is named.
TEST(WaitingResults, AFolderThatCannotTakeTheFileIsNamedAtTheFirstResultThatWaits) {
  const test::TestFolder folder;
  const fs::path missing = folder.path() / "missing";
  WaitingResults waiting(missing);
  try {
    waiting.put(1, 1, bytes(10, 1), {});
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(missing.string()), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace pss
