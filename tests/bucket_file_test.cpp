// Records sorted into buckets on disk (include/pss/io/bucket_file.hpp, issue 28): each
// bucket gives back its records in the order they came, whatever the buffers; the scratch
// file goes with the BucketFile, with an error, and with a signal.
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <vector>

#include "pss/core/error.hpp"
#include "pss/io/bucket_file.hpp"
#include "support/cli.hpp"

namespace pss {
namespace {

using BucketFileTest = test::CliTest;

struct Record {
  std::uint64_t index;
  float value[3];
};

bool folder_is_empty(const std::filesystem::path& folder) {
  return std::filesystem::directory_iterator(folder) == std::filesystem::directory_iterator();
}

TEST_F(BucketFileTest, EachBucketGivesItsRecordsInTheOrderTheyCame) {
  for (const std::size_t buffer : {std::size_t(1), std::size_t(7 * 3 * sizeof(Record)), std::size_t(1) << 20}) {
    SCOPED_TRACE(buffer);
    std::vector<std::vector<std::uint64_t>> expected(7);
    {
      BucketFile file(dir_, 7, sizeof(Record), buffer);
      for (std::uint64_t i = 0; i < 1000; ++i) {
        const int bucket = int((i * 2654435761u) % 7);
        const Record r{i, {float(i), -float(i), 0.5f}};
        file.append(bucket, &r);
        expected[std::size_t(bucket)].push_back(i);
        if (i == 500) {  // read while appending: the buffered records come last, in order
          std::vector<std::uint64_t> got;
          file.read(bucket, [&](std::span<const char> block) {
            for (std::size_t k = 0; k < block.size(); k += sizeof(Record)) {
              Record r2;
              std::memcpy(&r2, block.data() + k, sizeof r2);
              got.push_back(r2.index);
            }
          });
          EXPECT_EQ(got, expected[std::size_t(bucket)]);
        }
      }
      file.flush();
      EXPECT_TRUE(std::filesystem::exists(file.path()));
      for (int b = 0; b < 7; ++b) {
        EXPECT_EQ(file.records(b), expected[std::size_t(b)].size());
        std::vector<std::uint64_t> got;
        int blocks = 0;
        file.read(b, [&](std::span<const char> block) {
          ++blocks;
          ASSERT_EQ(block.size() % sizeof(Record), 0u);
          for (std::size_t k = 0; k < block.size(); k += sizeof(Record)) {
            Record r;
            std::memcpy(&r, block.data() + k, sizeof r);
            EXPECT_EQ(r.value[0], float(r.index));
            EXPECT_EQ(r.value[1], -float(r.index));
            got.push_back(r.index);
          }
        });
        EXPECT_EQ(got, expected[std::size_t(b)]) << "bucket " << b;
        if (buffer == 1) EXPECT_EQ(std::size_t(blocks), got.size()) << "a record a block";
        if (buffer == 7 * 3 * sizeof(Record)) EXPECT_EQ(std::size_t(blocks), (got.size() + 2) / 3);
      }
    }
    EXPECT_TRUE(folder_is_empty(dir_)) << "the scratch file outlived its BucketFile";
  }
}

TEST_F(BucketFileTest, TheScratchFileGoesWithAnErrorAndAFolderThatCannotTakeItIsNamed) {
  try {
    BucketFile file(dir_, 3, 8, 64);
    const std::uint64_t r = 1;
    file.append(0, &r);
    throw Error("a failure while the tiles are written");
  } catch (const Error&) {
  }
  EXPECT_TRUE(folder_is_empty(dir_));
  const std::string message = test::error_of([&] { BucketFile(dir_ / "missing", 3, 8, 64); });
  EXPECT_NE(message.find((dir_ / "missing").string()), std::string::npos) << message;
  EXPECT_NE(message.find("cannot write"), std::string::npos) << message;
  EXPECT_NE(test::error_of([&] { BucketFile(dir_, 0, 8, 64); }), "");
}

// A signal while the tiles are on disk (SIGTERM: SIGINT and SIGHUP, handled alike, are
// ignored where a test runs in the background or under nohup): the process dies of the
// signal, and its scratch file is gone.
TEST_F(BucketFileTest, ASignalRemovesTheScratchFile) {
  struct sigaction before {};
  ::sigaction(SIGTERM, nullptr, &before);
  if (before.sa_handler == SIG_IGN) GTEST_SKIP() << "SIGTERM is ignored here, and the handler leaves it so";
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    BucketFile file(dir_, 2, 8, 64);
    const std::uint64_t r = 7;
    for (int i = 0; i < 100; ++i) file.append(i % 2, &r);
    ::raise(SIGTERM);
    ::_exit(0);  // not reached: SIGTERM ends the process
  }
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGTERM) << status;
  EXPECT_TRUE(folder_is_empty(dir_));
}

}  // namespace
}  // namespace pss
