// The one check every numeric flag of every subcommand goes through. CLI11's Range and
// PositiveNumber compare with < and >, which NaN passes (and PositiveNumber lets infinity
// through): a NaN --fov became a voxel index and read out of bounds. These validators take
// only finite numbers in the range, and refuse anything else with one line naming the flag
// (CLI11 prefixes the flag's name), the range and the text given (quoted: printable, cut).
#pragma once

#include <CLI/CLI.hpp>
#include <cstdint>
#include <string>

namespace pss::app {

// A finite number x with lo <= x <= hi (lo < x when lo_open, also once x is a float: a
// tiny positive value that would become 0 is refused).
CLI::Validator finite_range(double lo, double hi, bool lo_open = false);

// A finite number that fits a float.
CLI::Validator finite_number();

// A finite number > 0 that fits a float.
CLI::Validator finite_positive();

// A size in bytes: a number with an optional K, M, G or T (powers of 1024; KB, KiB and the
// like too), such as 512M or 1.5G. Throws pss::Error naming --memory for anything else, and
// for less than 1 MiB or more than 2^60 bytes.
std::uint64_t parse_memory_size(const std::string& text);

// A flag whose text is parsed by `parse` (which throws pss::Error, e.g. parse_dims):
// checked while parsing, so a bad value is a usage error before any work.
template <class Parse>
CLI::Validator parsed_by(Parse parse, const std::string& flag, const std::string& type_name) {
  return CLI::Validator(
      [parse, flag](std::string& text) -> std::string {
        try {
          parse(text);
        } catch (const std::exception& e) {
          // The parser names the flag ("--dims '...': ..."); CLI11 names it too.
          std::string message = e.what();
          if (message.rfind(flag + " ", 0) == 0) message.erase(0, flag.size() + 1);
          return message;
        }
        return {};
      },
      type_name, flag);
}

}  // namespace pss::app
