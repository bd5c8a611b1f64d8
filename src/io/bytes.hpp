// A scalar from unaligned bytes in either byte order, for the binary readers (PLY, raw and
// NRRD volumes).
#pragma once

#include <algorithm>
#include <array>
#include <bit>
#include <cstring>

namespace pss::io {

// `swap` when the data's byte order is not the machine's.
template <class T>
T load(const char* bytes, bool swap) {
  std::array<char, sizeof(T)> raw;
  std::memcpy(raw.data(), bytes, sizeof(T));
  if (swap) std::reverse(raw.begin(), raw.end());
  return std::bit_cast<T>(raw);
}

}  // namespace pss::io
