// Files written byte by byte for the readers' tests: values in either byte order, and a LAS
// 1.2 file of point format 2.
#pragma once

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <string>
#include <vector>

namespace pss::test {

template <class T>
std::string bytes_of(T value, bool big_endian = false) {
  auto raw = std::bit_cast<std::array<char, sizeof(T)>>(value);
  if (big_endian != (std::endian::native == std::endian::big)) std::reverse(raw.begin(), raw.end());
  return std::string(raw.data(), raw.size());
}

// LAS 1.2, point format 2 (26-byte records with RGB), scale (0.01, 0.5, 0.25) and offset
// (100, −200, 1000), `gap` bytes (a VLR's) between the header and the points: point i at
// integers (1000i − 3, 4 − i, 8i), intensity 100 + i, class 6, colour (255i, 300, i) in
// 16-bit fields.
inline std::string las_12_format_2(int points, int gap) {
  std::string h = "LASF" + std::string(20, '\0') + bytes_of(std::uint8_t(1)) + bytes_of(std::uint8_t(2)) +
                  std::string(64, '\0') + bytes_of(std::uint16_t(1)) + bytes_of(std::uint16_t(2024)) +
                  bytes_of(std::uint16_t(227)) + bytes_of(std::uint32_t(227 + gap)) + bytes_of(std::uint32_t(0)) +
                  bytes_of(std::uint8_t(2)) + bytes_of(std::uint16_t(26)) + bytes_of(std::uint32_t(points)) +
                  std::string(20, '\0');
  for (const double s : {0.01, 0.5, 0.25}) h += bytes_of(s);
  for (const double o : {100.0, -200.0, 1000.0}) h += bytes_of(o);
  h += std::string(48, '\0') + std::string(std::size_t(gap), 'v');
  for (int i = 0; i < points; ++i) {
    h += bytes_of(std::int32_t(1000 * i - 3)) + bytes_of(std::int32_t(4 - i)) + bytes_of(std::int32_t(8 * i));
    h += bytes_of(std::uint16_t(100 + i)) + bytes_of(std::uint8_t(0)) + bytes_of(std::uint8_t(6)) + std::string(2, '\0');
    h += bytes_of(std::uint16_t(7));
    for (const int c : {255 * i, 300, i}) h += bytes_of(std::uint16_t(c));
  }
  return h;
}

}  // namespace pss::test
