#include "pss/points/noise.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <tuple>
#include <vector>

#include "pss/core/frame.hpp"
#include "pss/fit/inverse_power.hpp"
#include "pss/spatial/uniform_grid.hpp"

namespace pss {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Solves the symmetric 6×6 system a·x = b by Gaussian elimination with partial pivoting;
// false where a pivot falls below 1e-12 of the largest diagonal entry (a rank-deficient fit).
bool solve6(double a[6][6], double b[6]) {
  double scale = 0;
  for (int i = 0; i < 6; ++i) scale = std::max(scale, std::abs(a[i][i]));
  if (!(scale > 0)) return false;
  for (int col = 0; col < 6; ++col) {
    int pivot = col;
    for (int r = col + 1; r < 6; ++r)
      if (std::abs(a[r][col]) > std::abs(a[pivot][col])) pivot = r;
    if (!(std::abs(a[pivot][col]) > 1e-12 * scale)) return false;
    std::swap(a[col], a[pivot]);
    std::swap(b[col], b[pivot]);
    for (int r = col + 1; r < 6; ++r) {
      const double f = a[r][col] / a[col][col];
      for (int c = col; c < 6; ++c) a[r][c] -= f * a[col][c];
      b[r] -= f * b[col];
    }
  }
  for (int col = 5; col >= 0; --col) {
    for (int c = col + 1; c < 6; ++c) b[col] -= a[col][c] * b[c];
    b[col] /= a[col][col];
  }
  return true;
}

// The quadric height field's terms at local (x, y): z ≈ Σ cᵢ·termᵢ.
using Monomials = std::array<double, 6>;
Monomials monomials(glm::dvec3 l) { return {l.x * l.x, l.x * l.y, l.y * l.y, l.x, l.y, 1}; }

}  // namespace

double query_noise(const GridView& view, vec3 c, float reach) {
  thread_local std::vector<vec3> near;
  near.clear();
  view.for_each_in_radius(c, reach, [&](vec3 p, float, int) { near.push_back(p - c); });
  if (near.size() < std::size_t(kNoiseFit)) return kNaN;
  // In an order of their own, not the grid's: a cloud read tile by tile holds the same
  // points in another order, and gives the same σ to the last bit (tiles/spacing.hpp).
  std::sort(near.begin(), near.end(), [](vec3 a, vec3 b) {
    return std::tie(a.x, a.y, a.z) < std::tie(b.x, b.y, b.z);
  });
  WeightedMoments m(vec3(0.0f));
  for (const vec3& d : near) m.add_offset(d, 1.0f);
  const Sym3 covariance = m.covariance_about_mean();
  const EigenResult normal = smallest_eigenvector(covariance, vec3(0.0f));
  if (normal.status == EigenStatus::invalid) return kNaN;
  const Frame frame = Frame::from_normal(m.mean(), normal.vector);
  // In units of the reach, so that the normal equations' entries are of order one.
  double a[6][6] = {}, b[6] = {};
  thread_local std::vector<glm::dvec3> local;
  local.clear();
  for (const vec3& d : near) {
    const glm::dvec3 l = glm::dvec3(frame.to_local(d) / reach);
    local.push_back(l);
    const Monomials phi = monomials(l);
    for (int i = 0; i < 6; ++i) {
      for (int j = 0; j < 6; ++j) a[i][j] += phi[i] * phi[j];
      b[i] += phi[i] * l.z;
    }
  }
  if (!solve6(a, b)) return kNaN;
  thread_local std::vector<double> residual;
  residual.clear();
  for (const glm::dvec3& l : local) {
    const Monomials phi = monomials(l);
    double height = 0;
    for (int i = 0; i < 6; ++i) height += b[i] * phi[i];
    residual.push_back(std::abs(l.z - height));
  }
  const auto middle = residual.begin() + std::ptrdiff_t(residual.size() / 2);
  std::nth_element(residual.begin(), middle, residual.end());
  const double median = *middle;
  const auto quarter = residual.begin() + std::ptrdiff_t(residual.size() / 4);
  std::nth_element(residual.begin(), quarter, middle);
  const double count = double(residual.size());
  if (*quarter > sheets_quartile(count) * median) return kNaN;  // two sheets, not one noisy one
  return 1.4826 * median * std::sqrt(count / (count - 6)) * reach;
}

QueryNoise noise_near(const GridView& view, vec3 c, double kth) {
  QueryNoise out{kNaN, kth};
  const double farthest = kNoiseReachMost * kth;
  for (;;) {
    out.sigma = query_noise(view, c, float(out.reach));
    if (!std::isfinite(out.sigma)) return out;  // two sheets, a line: whatever the reach seen before
    const double wanted = std::min(kNoiseReach * out.sigma, farthest);
    if (!(wanted > out.reach * 1.1)) break;
    out.reach = wanted;
  }
  if (kNoiseReach * out.sigma > 1.1 * out.reach) out.sigma = kNaN;  // no slab within reach: a volume
  return out;
}

}  // namespace pss
