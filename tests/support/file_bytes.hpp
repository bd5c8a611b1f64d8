// Files written byte by byte for the readers' tests: values in either byte order, a LAS 1.2
// file of point format 2, a torus as XYZ text, and points as XYZ text.
#pragma once

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include <glm/ext/vector_double3.hpp>
#include <glm/geometric.hpp>

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

// A torus (R = 1, r = 0.35) of up to n points spread evenly over it, at (596700, 4000000, 0)
// so that a reader chooses an origin, as XYZ text in 12 decimals (doubles). `sparse_side`:
// only every 8th point where x < 0. `normal_length`: its normals that long (0: none).
inline std::string torus_xyz(int n, bool sparse_side, double normal_length) {
  std::string text;
  char line[240];
  for (int i = 0; i < n; ++i) {
    const double u = 2 * M_PI * std::fmod(0.6180339887 * i, 1.0), v = 2 * M_PI * std::fmod(0.7548776662 * i, 1.0);
    const glm::dvec3 n_(std::cos(v) * std::cos(u), std::cos(v) * std::sin(u), std::sin(v));
    const glm::dvec3 p = glm::dvec3(std::cos(u), std::sin(u), 0) + 0.35 * n_;
    if (sparse_side && p.x < 0 && i % 8 != 0) continue;
    int length = std::snprintf(line, sizeof line, "%.12f %.12f %.12f", 596700 + p.x, 4000000 + p.y, p.z);
    if (normal_length != 0)
      length += std::snprintf(line + length, sizeof line - std::size_t(length), " %g %g %g", normal_length * n_.x,
                              normal_length * n_.y, normal_length * n_.z);
    text.append(line, std::size_t(length));
    text += '\n';
  }
  return text;
}

// Points as XYZ text, each float in the digits that read back as it.
template <class Vec3>
std::string xyz_text(const std::vector<Vec3>& points) {
  std::string text;
  char line[100];
  for (const Vec3& p : points) {
    std::snprintf(line, sizeof line, "%.9g %.9g %.9g\n", double(p.x), double(p.y), double(p.z));
    text += line;
  }
  return text;
}

}  // namespace pss::test
