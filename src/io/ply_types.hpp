// The PLY scalar types by name, and what values they hold: shared by the reader (ply.cpp)
// and the writer (ply_write.cpp).
#pragma once

#include <charconv>
#include <cmath>
#include <cstddef>
#include <limits>
#include <optional>
#include <string>
#include <string_view>

#include "pss/io/ply.hpp"

namespace pss::io {

using Scalar = ScalarType;

struct TypeName {
  std::string_view name;
  Scalar type;
};
// Both the original PLY names and the sized ones that newer writers use; the original first.
inline constexpr TypeName kTypeNames[] = {
    {"char", Scalar::int8},     {"int8", Scalar::int8},       {"uchar", Scalar::uint8},
    {"uint8", Scalar::uint8},   {"short", Scalar::int16},     {"int16", Scalar::int16},
    {"ushort", Scalar::uint16}, {"uint16", Scalar::uint16},   {"int", Scalar::int32},
    {"int32", Scalar::int32},   {"uint", Scalar::uint32},     {"uint32", Scalar::uint32},
    {"float", Scalar::float32}, {"float32", Scalar::float32}, {"double", Scalar::float64},
    {"float64", Scalar::float64}};

inline std::optional<Scalar> scalar_named(std::string_view name) {
  for (const TypeName& e : kTypeNames)
    if (e.name == name) return e.type;
  return std::nullopt;
}

// The original name, which every PLY reader knows.
inline std::string_view name_of(Scalar type) {
  for (const TypeName& e : kTypeNames)
    if (e.type == type) return e.name;
  return {};
}

inline std::size_t size_of(Scalar type) {
  switch (type) {
    case Scalar::int8:
    case Scalar::uint8: return 1;
    case Scalar::int16:
    case Scalar::uint16: return 2;
    case Scalar::int32:
    case Scalar::uint32:
    case Scalar::float32: return 4;
    case Scalar::float64: return 8;
  }
  return 0;
}

template <class T>
inline bool whole_in_range(double v) {
  return v >= double(std::numeric_limits<T>::lowest()) && v <= double(std::numeric_limits<T>::max()) &&
         v == std::floor(v);
}

// v as a property of `type` holds it: rounded to float, or, for an integer type, only when
// whole and in range. Binary data always fits; ASCII text and values set in code may not.
inline std::optional<double> as_type(double v, Scalar type) {
  bool fits = true;
  switch (type) {
    case Scalar::float32: return double(float(v));
    case Scalar::float64: return v;
    case Scalar::int8: fits = whole_in_range<std::int8_t>(v); break;
    case Scalar::uint8: fits = whole_in_range<std::uint8_t>(v); break;
    case Scalar::int16: fits = whole_in_range<std::int16_t>(v); break;
    case Scalar::uint16: fits = whole_in_range<std::uint16_t>(v); break;
    case Scalar::int32: fits = whole_in_range<std::int32_t>(v); break;
    case Scalar::uint32: fits = whole_in_range<std::uint32_t>(v); break;
  }
  return fits ? std::optional(v) : std::nullopt;
}

inline std::string text_of(double v) {
  char text[32];
  return std::string(text, std::to_chars(text, text + sizeof text, v).ptr);
}

}  // namespace pss::io
