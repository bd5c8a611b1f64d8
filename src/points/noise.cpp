#include "pss/points/noise.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <cmath>
#include <limits>
#include <tuple>
#include <vector>

#include "pss/core/frame.hpp"
#include "pss/fit/inverse_power.hpp"
#include "pss/spatial/uniform_grid.hpp"

namespace pss {

namespace {

constexpr std::size_t kNoiseSlopeFit = 256;
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

NoiseAtReach query_noise(const GridView& view, vec3 c, float reach, float lateral) {
  thread_local std::vector<vec3> near;
  near.clear();
  view.for_each_in_radius(c, reach, [&](vec3 p, float, int) { near.push_back(p - c); });
  const NoiseAtReach none{kNaN, 0};
  // (A reach of 0: a query with 15 duplicates of itself, which no fixed point can scale.)
  if (near.size() < std::size_t(kNoiseFit) || !(reach > 0)) return none;
  // The principal plane from moments summed in fixed point, exactly: the same in any order
  // (a cloud read tile by tile holds the same points in another order, and gives the same σ
  // to the last bit, tiles/spacing.hpp).
  const double unit = double(1 << 20) / double(reach);
  __int128 first[3] = {0, 0, 0}, second[6] = {0, 0, 0, 0, 0, 0};
  for (const vec3& d : near) {
    const __int128 q[3] = {std::llround(double(d.x) * unit), std::llround(double(d.y) * unit),
                           std::llround(double(d.z) * unit)};
    for (int i = 0; i < 3; ++i) first[i] += q[i];
    second[0] += q[0] * q[0], second[1] += q[0] * q[1], second[2] += q[0] * q[2];
    second[3] += q[1] * q[1], second[4] += q[1] * q[2], second[5] += q[2] * q[2];
  }
  const double n = double(near.size());
  const glm::dvec3 mean(double(first[0]) / n, double(first[1]) / n, double(first[2]) / n);
  auto central = [&](int k, int i, int j) {
    return float((double(second[k]) / n - mean[i] * mean[j]) / (unit * unit));
  };
  const Sym3 covariance{central(0, 0, 0), central(1, 0, 1), central(2, 0, 2),
                        central(3, 1, 1), central(4, 1, 2), central(5, 2, 2)};
  const EigenResult normal = smallest_eigenvector(covariance, vec3(0.0f));
  if (normal.status == EigenStatus::invalid) return none;
  const Frame frame = Frame::from_normal(vec3(mean / unit), normal.vector);
  // The samples within `lateral` of the plane's normal through the mean, in an order of
  // their own (their sums below are rounded).
  const double within = std::min(1.0, double(lateral) / double(reach));  // in units of the reach
  thread_local std::vector<glm::dvec3> local;
  local.clear();
  for (const vec3& d : near) {
    const glm::dvec3 l = glm::dvec3(frame.to_local(d) / reach);
    if (l.x * l.x + l.y * l.y <= within * within) local.push_back(l);
  }
  std::sort(local.begin(), local.end(), [](const glm::dvec3& a, const glm::dvec3& b) {
    return std::tie(a.x, a.y, a.z) < std::tie(b.x, b.y, b.z);
  });
  // In units of the reach, so that the normal equations' entries are of order one.
  double a[6][6] = {}, b[6] = {};
  for (const glm::dvec3& l : local) {
    const Monomials phi = monomials(l);
    for (int i = 0; i < 6; ++i) {
      for (int j = 0; j < 6; ++j) a[i][j] += phi[i] * phi[j];
      b[i] += phi[i] * l.z;
    }
  }
  if (local.size() < std::size_t(kNoiseFit) || !solve6(a, b)) return none;
  thread_local std::vector<double> residual;
  residual.clear();
  for (const glm::dvec3& l : local) {
    const Monomials phi = monomials(l);
    double height = 0;
    for (int i = 0; i < 6; ++i) height += b[i] * phi[i];
    // The distance to the quadric, not its height above it: where the surface slopes within
    // the reach (a tube's flanks), the height takes the noise for more than it is (a torus's
    // tube of radius 6 kth with σ = 1.1 kth read 1.07σ, 0.99σ across). A fit of fewer samples
    // knows its slope too roughly for that (σ = kth/3 read 0.93σ with it, 1.0σ without).
    const double gx = 2 * b[0] * l.x + b[1] * l.y + b[3], gy = b[1] * l.x + 2 * b[2] * l.y + b[4];
    const double slope = local.size() >= kNoiseSlopeFit ? std::sqrt(1 + gx * gx + gy * gy) : 1.0;
    residual.push_back(std::abs(l.z - height) / slope);
  }
  const auto middle = residual.begin() + std::ptrdiff_t(residual.size() / 2);
  std::nth_element(residual.begin(), middle, residual.end());
  const double median = *middle;
  const auto quarter = residual.begin() + std::ptrdiff_t(residual.size() / 4);
  std::nth_element(residual.begin(), quarter, middle);
  const double count = double(residual.size());
  if (*quarter > sheets_quartile(count) * median) return none;  // two sheets, not one noisy one
  return {1.4826 * median * std::sqrt(count / (count - 6)) * reach, local.size()};
}

bool in_noise_level(vec3 p, int level) {
  // A 32-bit mix (murmur3's finaliser) of the coordinates' bits: the same floats choose alike
  // in core and in every tile.
  std::uint32_t h = std::bit_cast<std::uint32_t>(p.x);
  h = h * 0x9E3779B1u ^ std::bit_cast<std::uint32_t>(p.y);
  h = h * 0x9E3779B1u ^ std::bit_cast<std::uint32_t>(p.z);
  h ^= h >> 16;
  h *= 0x85EBCA6Bu;
  h ^= h >> 13;
  h *= 0xC2B2AE35u;
  h ^= h >> 16;
  return h < (0xFFFFFFFFu >> (3 * level));
}

NoiseGrids::NoiseGrids(std::span<const vec3> points, const GridView& all) {
  views_.level[0] = all;
  thinned_.reserve(kNoiseLevels - 1);
  // Each level's share lies within the one before (a lower bound on the same hash), so each
  // is chosen from that one's, in the same order.
  std::span<const vec3> finer = points;
  std::vector<vec3> share, coarser;
  for (int level = 1; level < kNoiseLevels; ++level) {
    coarser.clear();
    for (const vec3& p : finer)
      if (in_noise_level(p, level)) coarser.push_back(p);
    share.swap(coarser);
    finer = share;
    thinned_.emplace_back(share, 1e-7f, std::max<long long>(4096, (long long)share.size()));
    views_.level[level] = thinned_.back().view();
  }
}

QueryNoise noise_near(const NoiseViews& views, vec3 c, double kth) {
  QueryNoise out{kNaN, kth};
  const double farthest = kNoiseReachMost * kth;
  // How far from the query's axis a fit at `reach` takes samples.
  auto lateral = [&](double reach) {
    return std::min(reach, std::max(kNoiseLateral * kth, kNoiseLateralShare * reach));
  };
  int level = 0;
  for (;;) {
    const NoiseAtReach fit = query_noise(views.level[level], c, float(out.reach), float(lateral(out.reach)));
    out.sigma = fit.sigma;
    if (!std::isfinite(out.sigma)) return out;  // two sheets, a line: whatever the reach seen before
    const double wanted = std::min(kNoiseReach * out.sigma, farthest);
    if (!(wanted > out.reach * 1.1)) break;
    // A wider reach fits at least as many samples a lateral area, on a surface or in a
    // volume: the coarsest level that leaves kNoiseFitLeast of them.
    const double wider = lateral(wanted) / lateral(out.reach);
    const double fitted = double(fit.points) * double(1u << (3 * level)) * wider * wider;
    level = 0;
    while (level + 1 < kNoiseLevels && fitted >= kNoiseFitLeast * double(1u << (3 * (level + 1)))) ++level;
    out.reach = wanted;
  }
  if (kNoiseReach * out.sigma > 1.1 * out.reach) out.sigma = kNaN;  // no slab within reach: a volume
  return out;
}

}  // namespace pss
