// The command line: the subcommands' CLI11 options, our validators (apps/pss/numbers.hpp,
// --size, --view, --iterations, the raw-volume flags) and the checks of flags together
// (check_volume_options, raw_volume_format), on the app `pss` is (configure_app), with
// Action::check: a command whose options pass stops there, before it touches a file. The
// input is the arguments after "pss", separated by NUL bytes or newlines. A usage error
// (CLI::ParseError) or a pss::Error is the expected end of a bad command line; the message
// that the CLI would print is built too (failure_message, one_line).
#include <sstream>
#include <string>
#include <vector>

#include "commands.hpp"
#include "fuzz_input.hpp"

namespace {

constexpr std::size_t kMaxArguments = 256;

std::vector<std::string> arguments(std::string_view input) {
  std::vector<std::string> args{"pss"};
  std::size_t begin = 0;
  while (begin <= input.size() && args.size() <= kMaxArguments) {
    const std::size_t end = std::min(input.find_first_of(std::string_view("\0\n", 2), begin), input.size());
    args.emplace_back(input.substr(begin, end - begin));
    begin = end + 1;
  }
  return args;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace pss::fuzz;
  const std::vector<std::string> args = arguments(as_text(data, size));
  std::vector<const char*> argv;
  for (const std::string& a : args) argv.push_back(a.c_str());
  CLI::App app{"pss"};
  pss::app::configure_app(app, pss::app::Action::check);
  expect_value_or_error([&] {
    try {
      app.parse(int(argv.size()), argv.data());
    } catch (const CLI::ParseError& e) {
      std::ostringstream out, err;  // help, --version and usage errors, as main prints them
      app.exit(e, out, err);
      check_message(err.str().substr(0, err.str().empty() ? 0 : err.str().size() - 1));
    }
  });
  return 0;
}
