#include "pss/core/text.hpp"

#include <cfloat>
#include <cstdio>

namespace pss {

std::string printable(std::string_view text, std::size_t max_bytes) {
  static constexpr char kHex[] = "0123456789abcdef";
  std::string out;
  const std::size_t n = text.size() < max_bytes ? text.size() : max_bytes;
  out.reserve(n + 8);
  for (std::size_t i = 0; i < n; ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c == '\\') {
      out += "\\\\";
    } else if (c >= 0x20 && c < 0x7f) {
      out += char(c);
    } else {
      out += "\\x";
      out += kHex[c >> 4];
      out += kHex[c & 15];
    }
  }
  if (text.size() > n) out += "…";
  return out;
}

std::string format_number(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", x);
  return text;
}

std::string byte_size(double bytes) {
  char text[32];
  const bool gib = bytes >= double(1 << 30);
  std::snprintf(text, sizeof text, "%.4g %s", bytes / double(gib ? 1 << 30 : 1 << 20), gib ? "GiB" : "MiB");
  return text;
}

std::string range_text(double lo, double hi, bool lo_open) {
  const bool no_lo = lo == -double(FLT_MAX), no_hi = hi == double(FLT_MAX);
  if (no_lo && no_hi) return "a finite number";
  if (no_hi) return (lo_open ? "a finite number > " : "a finite number >= ") + format_number(lo);
  if (no_lo) return "a finite number <= " + format_number(hi);
  return lo_open ? "a finite number > " + format_number(lo) + " and <= " + format_number(hi)
                 : "a finite number from " + format_number(lo) + " to " + format_number(hi);
}

std::string quote(std::string_view text, std::size_t max_bytes) {
  // Appended, not "'" + ...: GCC 12 warns (-Wrestrict, a false positive) on operator+.
  std::string out = "'";
  out += printable(text, max_bytes);
  out += '\'';
  return out;
}

std::string one_line(std::string_view message, std::size_t max_bytes) {
  static constexpr char kHex[] = "0123456789abcdef";
  std::string out;
  std::size_t i = 0;
  for (; i < message.size(); ++i) {
    const auto c = static_cast<unsigned char>(message[i]);
    const bool control = c < 0x20 || c == 0x7f;
    if (out.size() + (control ? 4 : 1) > max_bytes) break;  // the bound is on what is printed
    if (control) {
      out += "\\x";
      out += kHex[c >> 4];
      out += kHex[c & 15];
    } else {
      out += char(c);
    }
  }
  if (i < message.size()) out += "…";
  return out;
}

}  // namespace pss
