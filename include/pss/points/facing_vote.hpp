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
// strays), and the highest point keeps its say. The sums are kept in fixed point: the same
// in any order, so that tiles sum to the in-core vote.
#pragma once

#include <algorithm>
#include <cmath>

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
  }
  // Another piece of the same part, its normals turned or not relative to this one's.
  void add(const FacingVote& other, bool turned) {
    up_ += turned ? -other.up_ : other.up_;
    height_up_ += turned ? -other.height_up_ : other.height_up_;
    level_ += other.level_;
    height_level_ += other.height_level_;
    lowest_ = std::min(lowest_, other.lowest_);
  }
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
  static __int128 fixed(double x) { return __int128(std::llround(std::clamp(x, -0x1p14, 0x1p14) * kScale)); }
  // Σ (z − z_lowest + δ) w from Σ z w and Σ w.
  long double weighed(__int128 height_sum, __int128 sum) const {
    return static_cast<long double>(height_sum) - (static_cast<long double>(lowest_) - kBelow) * static_cast<long double>(sum);
  }

  __int128 up_ = 0, height_up_ = 0;        // Σ n_z ρ², Σ z n_z ρ², in units of 2⁻⁴⁸
  __int128 level_ = 0, height_level_ = 0;  // the same of |n_z| ρ²: the terms' magnitudes
  float lowest_ = kInfinity;
};

}  // namespace pss
