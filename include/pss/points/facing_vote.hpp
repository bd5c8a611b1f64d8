// Which way a connected part of oriented normals faces. Hoppe et al. (1992) turn the highest
// point's normal to +z; a stray above the surface, whose normal no surface fitted, then
// decides for the whole part, and a noisy sphere with strays faced inward (docs/paper-notes.md).
// Instead every converged point votes. By the divergence theorem a closed surface facing
// outward encloses a positive volume, ∮ (z − z₀) n_z dA = V > 0 for any z₀; an open surface
// facing up (the ground, roofs) gives a positive sum as well once z₀ lies below it. So a part
// faces the way that makes Σ (z_i − z_lowest + δ) n_z,i ρ_i² positive, ρ_i² standing for the
// area a sample covers; strays' normals, of random sign, cancel. Where the sum is under a
// quarter of its terms' magnitudes (a sphere's is 2/3, an open surface's facing up near 1),
// the normals do not agree on a side (a part of a tree crown in an aerial scan, a few
// strays), and the highest point keeps its say. Beside them, the sums of the divergence
// theorem in all three axes say whether the points enclose a volume and which way (for
// closed parts and groups whose heights have no say, and for parts apart that together
// close one surface: close_the_parts). The sums are kept in fixed point: the same in any
// order, so that tiles sum to the in-core vote.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <span>
#include <vector>

#include "pss/core/types.hpp"
#include "pss/points/projection.hpp"

namespace pss {

class FacingVote {
 public:
  // A point of the part, at p (the unit frame) with its normal as oriented so far and 1/ρ² of
  // its support ρ, as a SupportGrid of the supports holds it (inv_h2 at κ = 1), so that tiles
  // weigh with the in-core floats; only a converged projection's normal is the surface's.
  void add(vec3 p, vec3 normal, float inv_rho2, ProjectionStatus status) {
    if (status != ProjectionStatus::converged) return;
    const double area = 1.0 / double(inv_rho2);
    const double z = std::clamp(double(p.z), -kFarthest, kFarthest);
    const double nz = double(normal.z) * area;
    if (!std::isfinite(nz) || !std::isfinite(z)) return;
    up_ += fixed(nz);
    height_up_ += fixed(z * nz);
    level_ += fixed(std::abs(nz));
    height_level_ += fixed(z * std::abs(nz));
    lowest_ = std::min(lowest_, float(z));
    area_ += fixed(area);
    double outward = 0;
    for (int k = 0; k < 3; ++k) {
      const double at = std::clamp(double(p[k]), -kFarthest, kFarthest), along = double(normal[k]) * area;
      if (!std::isfinite(at) || !std::isfinite(along)) continue;
      normal_[k] += fixed(along);
      position_[k] += fixed(at * area);
      outward += at * along;
    }
    outward_ += fixed(outward);
  }
  // Another piece of the same part, its normals turned or not relative to this one's.
  void add(const FacingVote& other, bool turned) {
    up_ += turned ? -other.up_ : other.up_;
    height_up_ += turned ? -other.height_up_ : other.height_up_;
    level_ += other.level_;
    height_level_ += other.height_level_;
    lowest_ = std::min(lowest_, other.lowest_);
    area_ += other.area_;
    for (int k = 0; k < 3; ++k) {
      normal_[k] += turned ? -other.normal_[k] : other.normal_[k];
      position_[k] += other.position_[k];
    }
    outward_ += turned ? -other.outward_ : other.outward_;
  }
  // Whether these points enclose a volume: their normals sum to under a fifth of their area
  // (a sphere: 0; the dragon 0.007 and the bunny 0.04, their bases open; a sphere's cap below
  // a gap of 0.3 radii apart from the rest: 0.1; a hemisphere 0.5; the ground and its roofs
  // near 1).
  bool encloses() const {
    long double sum2 = 0;
    for (int k = 0; k < 3; ++k) sum2 += static_cast<long double>(normal_[k]) * static_cast<long double>(normal_[k]);
    return area_ > 0 && sum2 <= kClosed * kClosed * static_cast<long double>(area_) * static_cast<long double>(area_);
  }
  // Where they do, +1 if they face outward as oriented: Σ (p − c)·n ρ² = 3V > 0 about their
  // centroid c (any c, by the divergence theorem in all three axes); −1 inward; 0 where they
  // do not enclose. It has a say where the heights' vote has none: a ring standing up, whose
  // top arc's underside faces down, gives 0.20 of its magnitudes there.
  int enclosing_sign() const {
    if (!encloses()) return 0;
    long double sum = static_cast<long double>(outward_);
    for (int k = 0; k < 3; ++k)
      sum -= static_cast<long double>(position_[k]) / static_cast<long double>(area_) * static_cast<long double>(normal_[k]);
    return sum > 0 ? 1 : (sum < 0 ? -1 : 0);
  }
  // Whether `part`, turned, leaves these points' normals a smaller sum than as it is: the side
  // on which a fragment apart from the rest closes the surface it belongs to.
  bool closes_turned(const FacingVote& part) const {
    long double along = 0;
    for (int k = 0; k < 3; ++k) along += static_cast<long double>(normal_[k]) * static_cast<long double>(part.normal_[k]);
    return along > 0;
  }
  long double area() const { return static_cast<long double>(area_); }
  // +1: the part faces as oriented; −1: it faces inward (or down) and turns; 0: no say (a
  // vertical wall, no converged point, normals that do not agree), where the highest point's
  // +z decides.
  int sign() const {
    if (lowest_ == kInfinity) return 0;
    const long double vote = weighed(height_up_, up_), magnitudes = weighed(height_level_, level_);
    if (!(std::abs(vote) >= kAgreement * magnitudes) || vote == 0) return 0;
    return vote > 0 ? 1 : -1;
  }

 private:
  static constexpr double kFarthest = 1024;  // unit frame: a projection thrown farther counts there
  static constexpr double kScale = 0x1p48;   // fixed point: ρ² ≥ 2⁻⁴⁰ still counts, |z n_z ρ²| < 2¹⁴
  static constexpr long double kBelow = 0x1p-10L;  // δ: a horizontal plane votes by its normals
  static constexpr long double kAgreement = 0.25L;
  static constexpr long double kClosed = 0.2L;
  static __int128 fixed(double x) { return __int128(std::llround(std::clamp(x, -0x1p14, 0x1p14) * kScale)); }
  // Σ (z − z_lowest + δ) w from Σ z w and Σ w.
  long double weighed(__int128 height_sum, __int128 sum) const {
    return static_cast<long double>(height_sum) - (static_cast<long double>(lowest_) - kBelow) * static_cast<long double>(sum);
  }

  __int128 up_ = 0, height_up_ = 0;        // Σ n_z ρ², Σ z n_z ρ², in units of 2⁻⁴⁸
  __int128 level_ = 0, height_level_ = 0;  // the same of |n_z| ρ²: the terms' magnitudes
  __int128 area_ = 0, outward_ = 0;        // Σ ρ², Σ p·n ρ²
  __int128 normal_[3] = {0, 0, 0}, position_[3] = {0, 0, 0};  // Σ n ρ², Σ p ρ²
  float lowest_ = kInfinity;
};

// Where a cloud's parts (each oriented, and turned where `turns` says by its own vote) together
// enclose a volume, the side each keeps is the one that closes it: the largest part's as its
// vote left it, then each next, the largest first (ties by `key(p)`, the cloud's index of its
// highest point), the side that leaves the normals' sum the smaller; then all face outward by
// the volume they enclose. A fragment of a closed scan apart from the rest (a cap below a
// gap) is an open surface to its own vote, which turns one that faces down to face up:
// inward. An open scene (the ground, its roofs and trees) encloses nothing, and each part
// keeps its vote. Parts without a converged point keep theirs too.
template <class Key>
void close_the_parts(std::span<const FacingVote> votes, Key key, std::vector<char>& turns) {
  std::vector<std::size_t> order;
  for (std::size_t p = 0; p < votes.size(); ++p)
    if (votes[p].area() > 0) order.push_back(p);
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return votes[a].area() > votes[b].area() || (votes[a].area() == votes[b].area() && key(a) < key(b));
  });
  FacingVote whole;
  std::vector<char> side(votes.size());
  for (std::size_t k = 0; k < order.size(); ++k) {
    const std::size_t p = order[k];
    side[p] = k == 0 ? turns[p] : char(whole.closes_turned(votes[p]));
    whole.add(votes[p], side[p] != 0);
  }
  const int outward = whole.enclosing_sign();
  if (outward == 0) return;
  for (const std::size_t p : order) turns[p] = char((side[p] != 0) != (outward < 0));
}

}  // namespace pss
