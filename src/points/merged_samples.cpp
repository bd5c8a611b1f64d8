#include "pss/points/merged_samples.hpp"

#include <algorithm>
#include <cmath>
#include <unordered_map>

namespace pss {

namespace {

struct Cube {
  int side;  // log2 of the side
  std::int64_t x, y, z;
  bool operator==(const Cube&) const = default;
};

struct CubeHash {
  std::size_t operator()(const Cube& c) const {
    std::uint64_t k = std::uint64_t(c.side) * 0x9E3779B97F4A7C15ull;
    for (const std::int64_t v : {c.x, c.y, c.z}) k = (k ^ std::uint64_t(v)) * 0xBF58476D1CE4E5B9ull + (k >> 29);
    return std::size_t(k);
  }
};

// The cube's index along one axis, held within int64 however small the side.
std::int64_t cube_index(float x, int side) {
  return std::int64_t(std::clamp(std::floor(std::ldexp(double(x), -side)), -0x1p62, 0x1p62));
}

Cube cube_of(vec3 p, float h) {
  const int side = std::ilogb(kMergeCell * h);
  return {side, cube_index(p.x, side), cube_index(p.y, side), cube_index(p.z, side)};
}

}  // namespace

MergedSamples merge_samples(std::span<const vec3> points, std::span<const float> h, std::span<const char> merge) {
  MergedSamples out;
  out.positions.assign(points.begin(), points.end());
  out.into.resize(points.size());
  struct Sum {
    int first;
    std::int64_t count = 0;
    double x = 0, y = 0, z = 0;
  };
  std::unordered_map<Cube, Sum, CubeHash> cubes;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const vec3 p = points[i];
    if (!merge[i] || !std::isfinite(h[i])) {
      out.into[i] = int(i);
      out.samples.push_back(int(i));
      continue;
    }
    Sum& s = cubes.try_emplace(cube_of(p, h[i]), Sum{int(i)}).first->second;
    out.into[i] = s.first;
    ++s.count;
    s.x += p.x;
    s.y += p.y;
    s.z += p.z;
  }
  for (const auto& [cube, s] : cubes) {
    const auto i = std::size_t(s.first);
    out.positions[i] = vec3(float(s.x / double(s.count)), float(s.y / double(s.count)), float(s.z / double(s.count)));
    out.samples.push_back(s.first);
  }
  std::sort(out.samples.begin(), out.samples.end());
  return out;
}

}  // namespace pss
