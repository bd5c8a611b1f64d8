#include "pss/points/visibility.hpp"

#include <algorithm>
#include <cmath>

#include "pss/backend/cpu/parallel_for.hpp"
#include "pss/core/error.hpp"

namespace pss {

namespace {

// A disc wider than this many voxels is marked this wide: a sample widened over a sparse
// region (adaptive support, up to 128 h) would otherwise mark millions.
constexpr float kWidestDisc = 32;
// Voxels left round the samples' box, so that the discs of the samples near its faces are
// marked up to this far out (wider ones are cut there).
constexpr int kMargin = 8;

// Two unit vectors that with n make an orthonormal basis.
void tangents(vec3 n, vec3& u, vec3& w) {
  const vec3 other = std::abs(n.x) < 0.9f ? vec3(1, 0, 0) : vec3(0, 1, 0);
  u = glm::normalize(glm::cross(n, other));
  w = glm::cross(n, u);
}

}  // namespace

namespace {

Aabb finite_box(std::span<const vec3> points) {
  Aabb box;
  for (const vec3 p : points)
    if (is_finite(p)) box.grow(p);
  return box;
}

}  // namespace

Occupancy::Occupancy(std::span<const vec3> points, std::span<const vec3> normals, std::span<const float> radius)
    : Occupancy(finite_box(points)) {
  mark(points, normals, radius);
}

Occupancy::Occupancy(const Aabb& box) : box_(box) {
  // No finite point, or a box no cloud has (inverted, or wider than a float: a hostile tile's
  // request): no voxels, every ray escapes.
  const vec3 extent = box.extent();
  if (!is_finite(box.lo) || !is_finite(box.hi) || !is_finite(extent) ||
      !glm::all(glm::greaterThanEqual(extent, vec3(0.0f))))
    return;
  const float longest = std::max({extent.x, extent.y, extent.z});
  cell_ = longest > 0 ? longest / float(kVisibilityCells - 2 * kMargin) : 1.0f;
  lo_ = box.lo - float(kMargin) * cell_;
  for (int a = 0; a < 3; ++a)  // clamped as a float, then cast
    dims_[a] = int(std::clamp(std::ceil((box.hi[a] - lo_[a]) / cell_) + float(kMargin), 1.0f, float(kVisibilityCells)));
  bits_.assign((std::size_t(dims_[0]) * std::size_t(dims_[1]) * std::size_t(dims_[2]) + 63) / 64, 0);
}

void Occupancy::mark(std::span<const vec3> points, std::span<const vec3> normals, std::span<const float> radius) {
  if (normals.size() != points.size() || radius.size() != points.size())
    throw Error("visibility: one normal and one radius per point are needed");
  if (bits_.empty()) return;
  cpu::parallel_for(std::int64_t(points.size()), [&](std::int64_t i) {
    const auto k = std::size_t(i);
    mark(points[k], normals[k], radius[k]);
  });
}

void Occupancy::set_words(std::vector<std::uint64_t>&& words) {
  if (words.size() != bits_.size()) throw Error("visibility: the occupancy's words do not fit its box");
  bits_ = std::move(words);
}

// The disc sampled every half voxel in its plane, so that a ray crossing it meets a marked
// voxel (sampled every two voxels, most rays slipped through between them).
void Occupancy::mark(vec3 p, vec3 normal, float r) {
  if (!is_finite(p)) return;
  const auto set = [&](vec3 at) {
    const vec3 g = (at - lo_) / cell_;
    for (int a = 0; a < 3; ++a)
      if (!(g[a] >= 0 && g[a] < float(dims_[a]))) return;  // outside the box, or not a number
    const std::size_t b = bit(int(g.x), int(g.y), int(g.z));
    __atomic_fetch_or(&bits_[b / 64], std::uint64_t(1) << (b % 64), __ATOMIC_RELAXED);
  };
  if (!has_direction(normal) || !(r > 0)) {
    set(p);
    return;
  }
  const vec3 n = glm::normalize(normal);
  vec3 u, w;
  tangents(n, u, w);
  const float reach = std::min(r, kWidestDisc * cell_), step = 0.5f * cell_;
  const int steps = int(std::ceil(reach / step));
  for (int a = -steps; a <= steps; ++a)
    for (int b = -steps; b <= steps; ++b) {
      const float s = float(a) * step, t = float(b) * step;
      if (s * s + t * t > reach * reach + step * step) continue;
      set(p + s * u + t * w);
    }
}

std::size_t Occupancy::bit(int x, int y, int z) const {
  return (std::size_t(z) * std::size_t(dims_[1]) + std::size_t(y)) * std::size_t(dims_[0]) + std::size_t(x);
}

bool Occupancy::occupied(int x, int y, int z) const {
  const std::size_t b = bit(x, y, z);
  return (bits_[b / 64] >> (b % 64)) & 1;
}

// Amanatides and Woo's voxel walk.
bool Occupancy::escapes(vec3 from, vec3 direction) const {
  if (bits_.empty()) return true;
  const vec3 g = (from - lo_) / cell_;
  int at[3], step[3];
  float next[3], delta[3];
  for (int a = 0; a < 3; ++a) {
    if (!(g[a] >= 0 && g[a] < float(dims_[a]))) return true;  // outside the box, or not a number
    at[a] = int(g[a]);
    const float d = direction[a];
    step[a] = d > 0 ? 1 : -1;
    delta[a] = d != 0 ? std::abs(1.0f / d) : kInfinity;
    const float to_face = d > 0 ? float(at[a] + 1) - g[a] : g[a] - float(at[a]);
    next[a] = d != 0 ? to_face * delta[a] : kInfinity;
  }
  for (;;) {
    if (occupied(at[0], at[1], at[2])) return false;
    const int a = next[0] < next[1] ? (next[0] < next[2] ? 0 : 2) : (next[1] < next[2] ? 1 : 2);
    at[a] += step[a];
    if (at[a] < 0 || at[a] >= dims_[a]) return true;  // out of the box
    next[a] += delta[a];
  }
}

std::vector<std::int8_t> visibility_votes(std::span<const vec3> points, std::span<const vec3> normals,
                                          std::span<const float> radius, Progress* progress) {
  return visibility_votes(Occupancy(points, normals, radius), points, normals, radius, progress);
}

std::vector<std::int8_t> visibility_votes(const Occupancy& occupancy, std::span<const vec3> points,
                                          std::span<const vec3> normals, std::span<const float> radius,
                                          Progress* progress) {
  if (normals.size() != points.size() || radius.size() != points.size())
    throw Error("visibility: one normal and one radius per point are needed");
  std::vector<std::int8_t> votes(points.size(), 0);
  const float past_voxels = 2.0f * occupancy.cell();
  cpu::parallel_for(std::int64_t(points.size()), [&](std::int64_t i) {
    const auto k = std::size_t(i);
    if (!has_direction(normals[k]) || !(radius[k] > 0)) return;
    const vec3 n = glm::normalize(normals[k]);
    vec3 u, w;
    tangents(n, u, w);
    const vec3 around[kVisibilityPairs] = {vec3(0.0f), u, -u, w, -w};
    const float start = 1.5f * radius[k] + past_voxels;
    int out = 0, in = 0;  // how many rays escape on the normal's side, and on the other
    for (const vec3 side : around) {
      const vec3 along = glm::normalize(std::cos(kVisibilityTilt) * n + std::sin(kVisibilityTilt) * side);
      out += occupancy.escapes(points[k] + start * along, along);
      in += occupancy.escapes(points[k] - start * along, -along);
    }
    votes[k] = std::int8_t(in == 0 ? out : (out == 0 ? -in : 0));
  }, progress);
  return votes;
}

std::vector<char> face_as_seen(std::span<const vec3> points, std::span<vec3> normals, std::span<const float> radius,
                               std::span<const int> part_of, std::size_t parts, const SpanningTree& tree,
                               Progress* progress) {
  if (part_of.size() != points.size()) throw Error("visibility: one part per point is needed");
  for (const int p : part_of)
    if (p < 0 || std::size_t(p) >= parts) throw Error("visibility: a point's part is out of range");
  const std::vector<std::int8_t> votes = visibility_votes(points, normals, radius, progress);
  std::vector<std::int64_t> size(parts, 0), voting(parts, 0);
  for (std::size_t k = 0; k < points.size(); ++k) {
    const auto p = std::size_t(part_of[k]);
    size[p] += 1;
    voting[p] += votes[k] != 0;
  }
  std::vector<char> decided(parts, 0);
  for (std::size_t p = 0; p < parts; ++p) decided[p] = rays_decide(voting[p], size[p]);
  const std::vector<char> turned = signs_along_tree(tree, votes, kCutVotes);
  for (std::size_t k = 0; k < points.size(); ++k)
    if (turned[k] && decided[std::size_t(part_of[k])]) normals[k] = -normals[k];
  return decided;
}

}  // namespace pss
