// Keyword arguments as the library's settings: each checked like the CLI's flag of the same
// name (a finite number in its range, or a one-line pss::Error naming the argument).
#pragma once

#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>

#include <pybind11/pybind11.h>

#include "pss/backend/backend.hpp"

namespace pss::python {

namespace py = pybind11;

// A library message as Python says it: the CLI's flags it names (--dims, --look-at) as the
// keyword arguments that set the same (dims, look_at).
std::string argument_names(const std::string& message);

// A value as a message shows it: its repr, printable and cut to one short line.
std::string shown(const py::handle& value);

// `options[key]`, which must be present (the Python layer passes every argument).
py::object option(const py::dict& options, const char* key);
bool is_given(const py::dict& options, const char* key);  // present and not None

// A finite number with lo <= x <= hi (lo < x when lo_open).
double number_in(const py::dict& options, const char* key, double lo, double hi, bool lo_open = false);
// `fallback` when None, else number_in.
double number_or(const py::dict& options, const char* key, double fallback, double lo, double hi, bool lo_open = false);
// None, or a finite number > 0.
std::optional<float> positive_or_none(const py::dict& options, const char* key);
int integer_in(const py::dict& options, const char* key, int lo, int hi);
bool flag(const py::dict& options, const char* key);
std::string text(const py::dict& options, const char* key);
// One of `choices`.
std::string choice(const py::dict& options, const char* key, std::initializer_list<std::string_view> choices);

Backend backend_of(const py::dict& options);  // "backend": auto, cpu or cuda

}  // namespace pss::python
