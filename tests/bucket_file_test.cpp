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

// Ctrl-C while the tiles are on disk: the process dies of the signal, and its scratch file
// is gone.
TEST_F(BucketFileTest, ASignalRemovesTheScratchFile) {
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    ::signal(SIGINT, SIG_DFL);  // as at a terminal, not under nohup (which the handler leaves alone)
    BucketFile file(dir_, 2, 8, 64);
    const std::uint64_t r = 7;
    for (int i = 0; i < 100; ++i) file.append(i % 2, &r);
    struct sigaction handler {};
    ::sigaction(SIGINT, nullptr, &handler);
    if (handler.sa_handler == SIG_DFL) ::_exit(77);  // this process installed it before, under nohup
    ::raise(SIGINT);
    ::_exit(0);  // not reached: SIGINT ends the process
  }
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  if (WIFEXITED(status) && WEXITSTATUS(status) == 77) {
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
    GTEST_SKIP() << "the handler was left alone in this process (SIGINT ignored when it was installed)";
  }
  EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGINT) << status;
  EXPECT_TRUE(folder_is_empty(dir_));
}

}  // namespace
}  // namespace pss
