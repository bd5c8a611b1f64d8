#include "support/cli.hpp"

#include <sys/wait.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
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

CliResult run_pss(const std::string& args) {
  static int counter = 0;
  const auto dir = std::filesystem::temp_directory_path();
  const auto base = "pss-cli-" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
  const auto out = dir / (base + ".out"), err = dir / (base + ".err");
  const std::string command = std::string(PSS_CLI) + " " + args + " >" + out.string() + " 2>" + err.string();
  const int status = std::system(command.c_str());
  CliResult r{WIFEXITED(status) ? WEXITSTATUS(status) : 128, slurp(out), slurp(err)};
  std::filesystem::remove(out);
  std::filesystem::remove(err);
  return r;
}

int line_count(const std::string& s) { return int(std::count(s.begin(), s.end(), '\n')); }

}  // namespace pss::test
