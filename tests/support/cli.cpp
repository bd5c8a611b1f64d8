#include "support/cli.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>

namespace pss::test {

namespace {
std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}
}  // namespace

CliResult run_pss(const std::string& args) { return run_shell(std::string(PSS_CLI) + " " + args); }

CliResult run_shell(const std::string& command_line) {
  static int counter = 0;
  const auto dir = std::filesystem::temp_directory_path();
  const auto base = "pss-cli-" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
  const auto out = dir / (base + ".out"), err = dir / (base + ".err");
  const std::string command = command_line + " >" + out.string() + " 2>" + err.string();
  const int status = std::system(command.c_str());
  CliResult r{WIFEXITED(status) ? WEXITSTATUS(status) : 128, slurp(out), slurp(err)};
  std::filesystem::remove(out);
  std::filesystem::remove(err);
  return r;
}

int line_count(const std::string& s) { return int(std::count(s.begin(), s.end(), '\n')); }

void CliTest::SetUp() {
  const std::string name = testing::UnitTest::GetInstance()->current_test_info()->name();
  dir_ = std::filesystem::temp_directory_path() / ("pss-" + name + "-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir_);
}

void CliTest::TearDown() { std::filesystem::remove_all(dir_); }

std::string CliTest::write(const std::string& name, const std::string& bytes) const {
  std::ofstream(path(name), std::ios::binary) << bytes;
  return path(name);
}

std::string CliTest::read(const std::string& file) const {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void CliTest::expect_clean_failure(const std::string& args, const std::string& names, const std::string& output) {
  const CliResult r = run_pss(args);
  EXPECT_NE(r.exit_code, 0) << args;
  EXPECT_EQ(line_count(r.err), 1) << r.err;
  EXPECT_NE(r.err.find(names), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("internal error"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(output)) << output;
  for (const auto& entry : std::filesystem::directory_iterator(dir_))
    EXPECT_EQ(entry.path().filename().string().find(".tmp"), std::string::npos) << entry.path();
}

TestFolder::TestFolder() {
  const testing::TestInfo* test = testing::UnitTest::GetInstance()->current_test_info();
  const std::string name = test ? std::string(test->test_suite_name()) + "-" + test->name() : "outside-a-test";
  path_ = std::filesystem::temp_directory_path() / ("pss-" + name + "-" + std::to_string(::getpid()));
  std::filesystem::create_directories(path_);
}

TestFolder::~TestFolder() {
  std::error_code ignored;
  std::filesystem::remove_all(path_, ignored);
}

ScratchFolder::ScratchFolder(const std::filesystem::path& path) : path_(path) {
  std::filesystem::create_directories(path);
  if (const char* old = std::getenv("TMPDIR")) old_ = old;
  setenv("TMPDIR", path.c_str(), 1);
}

ScratchFolder::~ScratchFolder() { old_.empty() ? unsetenv("TMPDIR") : setenv("TMPDIR", old_.c_str(), 1); }

}  // namespace pss::test
