// Running the pss binary from tests: exit status and what it printed.
#pragma once

#include <string>

namespace pss::test {

struct CliResult {
  int exit_code;
  std::string out;  // stdout
  std::string err;  // stderr
};

// Runs `pss <args>` through the shell (args are passed as written).
CliResult run_pss(const std::string& args);

// Count of '\n' in s: a one-line message has exactly one.
int line_count(const std::string& s);

}  // namespace pss::test
