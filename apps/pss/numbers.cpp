#include "numbers.hpp"

#include <cerrno>
#include <cctype>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "pss/core/error.hpp"
#include "pss/core/text.hpp"

namespace pss::app {

namespace {

// What --help shows after a flag's type: its range where both ends are finite, as CLI11's
// own ranges show theirs ("NUMBER in [1 - 170]").
std::string range_name(double lo, double hi, bool lo_open) {
  if (hi == double(FLT_MAX)) return lo_open && lo == 0 ? "POSITIVE" : "NUMBER";
  if (lo == -double(FLT_MAX)) return "NUMBER";
  return std::string("NUMBER in ") + (lo_open ? "(" : "[") + format_number(lo) + " - " + format_number(hi) + "]";
}

}  // namespace

CLI::Validator finite_range(double lo, double hi, bool lo_open) {
  const std::string range = range_text(lo, hi, lo_open);
  return CLI::Validator(
      [lo, hi, lo_open, range](std::string& text) -> std::string {
        const char* begin = text.c_str();
        char* end = nullptr;
        errno = 0;
        const double x = std::strtod(begin, &end);
        const bool parsed = end != begin && *end == '\0' && !std::isspace(static_cast<unsigned char>(*begin));
        if (!parsed || !std::isfinite(x) || errno == ERANGE || x > hi || (lo_open ? !(x > lo) : !(x >= lo)))
          return "expected " + range + " (got " + quote(text) + ")";
        // The flags hold floats: a positive value below float's range becomes 0, which for
        // --h, --rho, --b and --epsilon means "the default" (--h 1e-50 was accepted so), and
        // one below its normal range makes lengths of 0 (--h 1e-45: "epsilon must be positive").
        if (lo_open && !(float(x) > float(lo)))
          return "expected " + range + " (got " + quote(text) + ", which is " + format_number(float(x)) + " as a float)";
        if (lo_open && lo == 0 && float(x) < FLT_MIN)
          return "expected " + range + " (got " + quote(text) + ", below a float's normal range)";
        return {};
      },
      range_name(lo, hi, lo_open), "finite range");
}

std::uint64_t parse_memory_size(const std::string& text) {
  const auto refuse = [&text](const std::string& why) {
    return Error("--memory " + quote(text) + ": " + why);
  };
  const char* begin = text.c_str();
  char* end = nullptr;
  errno = 0;
  const double number = std::strtod(begin, &end);
  if (end == begin || std::isspace(static_cast<unsigned char>(*begin)) || !std::isfinite(number) || errno == ERANGE)
    throw refuse("expected a size such as 512M or 8G");
  std::string unit(end);
  for (char& c : unit) c = char(std::toupper(static_cast<unsigned char>(c)));
  double scale = 1;
  if (!unit.empty() && unit != "B") {
    const std::string units = "KMGT";
    const std::size_t power = units.find(unit[0]);
    const std::string rest = unit.substr(1);
    if (power == std::string::npos || !(rest.empty() || rest == "B" || rest == "IB"))
      throw refuse("expected a size such as 512M or 8G");
    scale = std::ldexp(1.0, 10 * int(power + 1));
  }
  const double bytes = number * scale;
  if (!(bytes >= double(1 << 20)) || bytes > std::ldexp(1.0, 60))
    throw refuse("expected at least 1M and at most 2^60 bytes");
  return std::uint64_t(bytes);
}

CLI::Validator finite_positive() { return finite_range(0, double(FLT_MAX), true); }

CLI::Validator finite_number() { return finite_range(-double(FLT_MAX), double(FLT_MAX)); }

}  // namespace pss::app
