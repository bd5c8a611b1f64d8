// Running the pss binary from tests: exit status and what it printed.
#pragma once

#include <filesystem>
#include <string>

#include <gtest/gtest.h>

namespace pss::test {

struct CliResult {
  int exit_code;
  std::string out;  // stdout
  std::string err;  // stderr
};

// Runs `pss <args>` through the shell (args are passed as written).
CliResult run_pss(const std::string& args);
// Runs a shell command line; its exit status and what it printed.
CliResult run_shell(const std::string& command_line);

// Count of '\n' in s: a one-line message has exactly one.
int line_count(const std::string& s);

// A fixture with a private folder for a test's files (removed afterwards) and the CLI's
// failure contract.
class CliTest : public testing::Test {
 protected:
  void SetUp() override;
  void TearDown() override;
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  // Writes `bytes` to the folder's file `name`; returns its path.
  std::string write(const std::string& name, const std::string& bytes) const;
  // The bytes of `file` ("" if it cannot be read).
  std::string read(const std::string& file) const;
  // Exit non-zero, one line on stderr naming `names` and no internal error, no `output`
  // file and no temporary left in the folder.
  void expect_clean_failure(const std::string& args, const std::string& names, const std::string& output);
  std::filesystem::path dir_;
};

// A folder of the running test's own under the system's temporary folder, removed with
// everything in it when the object goes.
class TestFolder {
 public:
  TestFolder();
  ~TestFolder();
  TestFolder(const TestFolder&) = delete;
  TestFolder& operator=(const TestFolder&) = delete;
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

// $TMPDIR set to a folder of the test's while it lives (the tiles' scratch files go there).
class ScratchFolder {
 public:
  explicit ScratchFolder(const std::filesystem::path& path);
  ~ScratchFolder();
  bool empty() const { return std::filesystem::is_empty(path_); }

 private:
  std::filesystem::path path_;
  std::string old_;
};

// The message of the pss::Error that f() throws, or "" if it throws none.
template <class F>
std::string error_of(F&& f);

}  // namespace pss::test

#include "pss/core/error.hpp"

template <class F>
std::string pss::test::error_of(F&& f) {
  try {
    f();
  } catch (const pss::Error& e) {
    return e.what();
  }
  return "";
}
