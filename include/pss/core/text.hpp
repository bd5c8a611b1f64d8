// Quoting what a user supplied (a flag's value, a header's field, a file's name) inside a
// one-line error message: every byte outside printable ASCII becomes \xNN, so a newline or a
// terminal escape in the input cannot break the line or the terminal, and the text is cut
// after a bounded number of bytes with "…", so a 20 MB header line is not echoed whole.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace pss {

// The longest input echoed by quote(): enough to recognise a value, short enough for a line.
inline constexpr std::size_t kQuotedBytes = 80;

// `text` with non-printable bytes as \xNN (a backslash as \\, so an escape is unambiguous),
// the first `max_bytes` bytes of it only, then "…" when there were more.
std::string printable(std::string_view text, std::size_t max_bytes = kQuotedBytes);

// x as messages print it (%g).
std::string format_number(double x);

// A number of bytes in MiB, or GiB from 1 GiB, four digits at most: "3.291 MiB", "12 GiB".
std::string byte_size(double bytes);

// The numbers a value must be, as messages name them ("a finite number > 0"): from lo (or
// above it, lo_open) to hi, where ±FLT_MAX leaves that side unbounded. The CLI's flags and
// the Python module's arguments say it the same way.
std::string range_text(double lo, double hi, bool lo_open);

// printable(text) between single quotes: 'text'.
std::string quote(std::string_view text, std::size_t max_bytes = kQuotedBytes);

// A whole message made safe to print as one line: control bytes (a newline, an escape) as
// \xNN, the rest as is (quote() already escaped what the message echoes), cut with "…"
// where the result would pass `max_bytes` (escapes counted as printed). For text that did
// not pass through quote(), e.g. CLI11's messages, which echo the argument they refuse.
std::string one_line(std::string_view message, std::size_t max_bytes = 1024);

}  // namespace pss
