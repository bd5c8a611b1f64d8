#include "options.hpp"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <regex>

#include "pss/core/error.hpp"
#include "pss/core/text.hpp"

namespace pss::python {

namespace {

Error bad(const char* key, const std::string& expected, const py::handle& value) {
  return Error(std::string(key) + ": expected " + expected + " (got " + shown(value) + ")");
}

}  // namespace

std::string argument_names(const std::string& message) {
  static const std::regex flag(R"((^|[\s'"(,/])--([a-z][a-z0-9-]*))");
  std::string out;
  auto last = message.cbegin();
  for (std::sregex_iterator it(message.begin(), message.end(), flag), end; it != end; ++it) {
    out.append(last, (*it)[0].first);
    std::string name = (*it)[2].str();
    std::replace(name.begin(), name.end(), '-', '_');
    out += (*it)[1].str() + name;
    last = (*it)[0].second;
  }
  return out.append(last, message.cend());
}

std::string shown(const py::handle& value) { return printable(py::str(py::repr(value)).cast<std::string>(), 80); }

py::object option(const py::dict& options, const char* key) {
  if (!options.contains(key)) throw Error(std::string("internal: the argument '") + key + "' was not passed");
  return options[key];
}

bool is_given(const py::dict& options, const char* key) { return !option(options, key).is_none(); }

double number_in(const py::dict& options, const char* key, double lo, double hi, bool lo_open) {
  const py::object value = option(options, key);
  const std::string range = range_text(lo, hi, lo_open);
  if (py::isinstance<py::bool_>(value) || !(py::isinstance<py::float_>(value) || py::isinstance<py::int_>(value) ||
                                           py::hasattr(value, "__float__")))
    throw bad(key, range, value);
  const double x = value.cast<double>();
  // As float, as the library holds it: a positive value that would become 0, or a length
  // below float's normal range (whose thousandth, ε, is 0), is refused.
  if (!std::isfinite(x) || x > hi || (lo_open ? !(float(x) > float(lo)) : !(x >= lo)) ||
      (lo_open && lo == 0 && float(x) < FLT_MIN))
    throw bad(key, range, value);
  return x;
}

double number_or(const py::dict& options, const char* key, double fallback, double lo, double hi, bool lo_open) {
  return is_given(options, key) ? number_in(options, key, lo, hi, lo_open) : fallback;
}

std::optional<float> positive_or_none(const py::dict& options, const char* key) {
  if (!is_given(options, key)) return std::nullopt;
  return float(number_in(options, key, 0, double(FLT_MAX), true));
}

int integer_in(const py::dict& options, const char* key, int lo, int hi) {
  const py::object value = option(options, key);
  const std::string range = "an integer from " + std::to_string(lo) + " to " + std::to_string(hi);
  if (py::isinstance<py::bool_>(value) || !py::hasattr(value, "__index__")) throw bad(key, range, value);
  const py::int_ i(value.attr("__index__")());
  if (i < py::int_(lo) || i > py::int_(hi)) throw bad(key, range, value);
  return i.cast<int>();
}

bool flag(const py::dict& options, const char* key) {
  const py::object value = option(options, key);
  if (!py::isinstance<py::bool_>(value)) throw bad(key, "True or False", value);
  return value.cast<bool>();
}

std::string text(const py::dict& options, const char* key) {
  const py::object value = option(options, key);
  if (!py::isinstance<py::str>(value)) throw bad(key, "a string", value);
  return value.cast<std::string>();
}

std::string choice(const py::dict& options, const char* key, std::initializer_list<std::string_view> choices) {
  const py::object value = option(options, key);
  if (py::isinstance<py::str>(value)) {
    const std::string s = value.cast<std::string>();
    if (std::find(choices.begin(), choices.end(), s) != choices.end()) return s;
  }
  std::string listed;
  for (std::string_view c : choices) listed += (listed.empty() ? "'" : ", '") + std::string(c) + "'";
  throw bad(key, "one of " + listed, value);
}

Backend backend_of(const py::dict& options) { return select_backend(choice(options, "backend", {"auto", "cpu", "cuda"})); }

}  // namespace pss::python
