// Where the bulk of a cloud's positions lies, from a fixed sample: a few points far from the
// rest (a scanner's (0,0,0) beside a georeferenced scan, a stray at 10⁶ beside the bunny)
// decide neither the origin the readers choose (points/cloud.hpp) nor the unit frame
// (points/unit_frame.hpp), which took the box's centre and rounded the rest to the float
// steps at the stray's distance (a new user's trial: urban.las with one point at zero was
// read on quarter-metre steps). At most 4,096 positions are kept by reservoir sampling
// (Algorithm R) with a fixed seed, so that a file read whole and the same file streamed into
// tiles (io/tiled_cloud.hpp) keep the same ones and agree to the bit.
#pragma once

#include <cstdint>
#include <random>
#include <vector>

#include <glm/ext/vector_double3.hpp>

namespace pss {

class BulkSample {
 public:
  void add(const glm::dvec3& p) {
    ++seen_;
    if (kept_.size() < kKept) {
      kept_.push_back(p);
      return;
    }
    const std::uint64_t j = random_() % seen_;
    if (j < kKept) kept_[std::size_t(j)] = p;
  }
  const std::vector<glm::dvec3>& kept() const { return kept_; }

  // Of a set of positions (the kept ones, or those made of them): per axis the median and the
  // 2nd and 98th percentiles, the box of the bulk; zero for none.
  struct Bulk {
    glm::dvec3 lo{0.0}, hi{0.0}, median{0.0};
  };
  static Bulk bulk_of(std::vector<glm::dvec3> positions);
  // Whether the box [lo, hi] of every position is the strays', not the bulk's: its centre lies
  // farther from the bulk's median than the bulk's extent along some axis (then it stands where
  // there are no data). Else the box's centre serves, as it did before: the same floats.
  static bool box_of_strays(const Bulk& bulk, const glm::dvec3& lo, const glm::dvec3& hi);

 private:
  static constexpr std::size_t kKept = 4096;
  std::vector<glm::dvec3> kept_;
  std::uint64_t seen_ = 0;
  std::mt19937_64 random_{20261130};
};

}  // namespace pss
