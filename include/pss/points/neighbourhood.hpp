// The neighbourhood N(r) of a point with its Gaussian weights θ3(‖pᵢ − r‖) = mᵢ·exp(−‖pᵢ − r‖²/hᵢ²)
// (mᵢ the points a merged sample stands for, points/merged_samples.hpp; 1 for all others):
// the samples whose support holds r (‖pᵢ − r‖ ≤ ρᵢ; one global h gives every sample the
// same, the paper's ρ-neighbourhood), gathered once: every sum of one projection runs over
// the same samples (Eq. 1, 2 and the polynomial), so later passes need no grid walk, and
// those weighted from r no exp(). A fixed-size buffer (no allocation, usable in kernels); a
// neighbourhood larger than it is read from the grid again, with the same samples and
// weights.
//
// The samples are kept as offsets from r, one array per coordinate, so that the weights
// and the sums over them run in SIMD lanes on the CPU; the gather stores every candidate
// of the grid cells and keeps it only when covered, with no branch to mispredict.
#pragma once

#include "pss/core/frame.hpp"
#include "pss/fit/moments.hpp"
#include "pss/fit/polynomial.hpp"
#include "pss/fit/weights.hpp"
#include "pss/spatial/support_grid.hpp"

namespace pss {

template <int Capacity>
struct NeighbourhoodOf {
  static constexpr int kCapacity = Capacity;

  const SupportGridView* grid;
  vec3 center;
  int count = 0;
  // Slot Capacity takes the candidates the gather rejects once the buffer is full; the
  // slots after the last sample, up to a multiple of the sum lanes, hold zeros (add_all).
  static constexpr int kSlots = Capacity + PSS_SUM_LANES;
  float dx[kSlots], dy[kSlots], dz[kSlots], weight[kSlots], inv_h2[kSlots], mass[kSlots];
  bool massive;  // mass[] is filled (the grid has masses); otherwise every mass is 1

  PSS_HOST_DEVICE NeighbourhoodOf(const SupportGridView& g, vec3 c) : grid(&g), center(c), massive(g.mass != nullptr) {
    // The masses only where the cloud has merged samples: others pay no load, store or
    // multiply for them in the gather, the hot loop of every projection.
    if (massive)
      gather<true>();
    else
      gather<false>();
  }

  PSS_HOST_DEVICE bool overflowed() const { return count > Capacity; }
  PSS_HOST_DEVICE int stored() const { return count < Capacity ? count : Capacity; }

  // f(p, w, 1/h², m) for every sample again, in the same order.
  template <class F>
  PSS_HOST_DEVICE void for_each(F&& f) const {
    if (!overflowed() && massive) {
      for (int i = 0; i < count; ++i) f(center + vec3(dx[i], dy[i], dz[i]), weight[i], inv_h2[i], mass[i]);
    } else if (!overflowed()) {
      // A constant mass, which the callers' products by it fold away (MlsEnergy, Brent's).
      for (int i = 0; i < count; ++i) f(center + vec3(dx[i], dy[i], dz[i]), weight[i], inv_h2[i], 1.0f);
    } else {
      grid->for_each_covering(center, [&](vec3 p, float d2, int i) {
        const float q = grid->inv_h2[i];
        const float m = grid->mass_of(i);
        f(p, m * gaussian_weight(d2, q), q, m);
      });
    }
  }

  // Σw, Σw·(p − r), Σw·(p − r)(p − r)ᵀ with the weights from r (Eq. 1 at r), and Σw/h².
  PSS_HOST_DEVICE WeightedMoments moments() const {
    WeightedMoments m(center);
    if (!overflowed()) {
      m.add_all(count, [&](int i) { return vec3(dx[i], dy[i], dz[i]); }, [&](int i) { return weight[i]; });
      for (int i = 0; i < count; ++i) m.inv_h2_sum += weight[i] * inv_h2[i];
    } else {
      for_each([&](vec3 p, float w, float q, float) {
        m.add(p, w);
        m.inv_h2_sum += w * q;
      });
    }
    return m;
  }

  // The polynomial's normal equations in `frame` (x, y in units of `scale`), weighted from r
  // or, with weights_at_origin, from the frame's origin q (the MLS polynomial).
  PSS_HOST_DEVICE PolynomialFit polynomial_fit(const Frame& frame, bool weights_at_origin, float scale) const {
    PolynomialFit fit(scale);
    if (!overflowed()) {
      const vec3 o = frame.to_local(center);
      auto local = [&](int i) { return o + frame.direction_to_local(vec3(dx[i], dy[i], dz[i])); };
      if (weights_at_origin && massive)
        // The padding's weight must be 0 (add_all): its mass is.
        fit.add_all(count, local, [&](int i) { return mass[i] * gaussian_weight(length2(local(i)), inv_h2[i]); });
      else if (weights_at_origin)
        // A factor, not a branch, so that it vectorises.
        fit.add_all(count, local, [&](int i) { return gaussian_weight(length2(local(i)), inv_h2[i]) * (i < count ? 1.0f : 0.0f); });
      else
        fit.add_all(count, local, [&](int i) { return weight[i]; });
    } else {
      for_each([&](vec3 p, float w_r, float q, float m) {
        const vec3 l = frame.to_local(p);
        fit.add(l, weights_at_origin ? m * gaussian_weight(length2(l), q) : w_r);
      });
    }
    return fit;
  }

 private:
  template <bool kMassive>
  PSS_HOST_DEVICE void gather() {
    grid->for_each_near(center, [&](vec3 p, int i) {
      const vec3 d = p - center;
      const float d2 = length2(d);
      const float q = grid->inv_h2[i];
      const int slot = count < Capacity ? count : Capacity;
      dx[slot] = d.x;
      dy[slot] = d.y;
      dz[slot] = d.z;
      weight[slot] = d2;
      inv_h2[slot] = q;
      if constexpr (kMassive) mass[slot] = grid->mass[i];
      count += grid->covers(i, d2) ? 1 : 0;
    });
    const int n = stored();
    for (int i = 0; i < n; ++i) weight[i] = gaussian_weight(weight[i], inv_h2[i]);
    if constexpr (kMassive)
      for (int i = 0; i < n; ++i) weight[i] *= mass[i];
    for (int i = n; i % PSS_SUM_LANES != 0; ++i) dx[i] = dy[i] = dz[i] = weight[i] = inv_h2[i] = mass[i] = 0;
  }
};

// The same N(r) kept as the grid's indices of its samples, 4 bytes each against the 16 of an
// offset and a weight: what a GPU thread keeps, whose stack lives in local memory (a budget
// of 1 KiB per thread, tests/gpu/kernel_stacks.py). Each pass reads the samples from the
// grid's sorted array, which neighbouring threads share in cache, and weighs them again.
template <int Capacity>
struct NeighbourIndicesOf {
  static constexpr int kCapacity = Capacity;

  const SupportGridView* grid;
  vec3 center;
  int count = 0;
  int index[Capacity > 0 ? Capacity : 1];

  PSS_HOST_DEVICE NeighbourIndicesOf(const SupportGridView& g, vec3 c) : grid(&g), center(c) {
    grid->for_each_covering(center, [&](vec3, float, int i) {
      if (count < Capacity) index[count] = i;
      ++count;
    });
  }

  PSS_HOST_DEVICE bool overflowed() const { return count > Capacity; }

  // f(p, sorted index) for every sample again, in the same order: for the fits that read
  // more of a sample than its position (its normal) and weigh it from elsewhere than r.
  template <class F>
  PSS_HOST_DEVICE void for_each_sample(F&& f) const {
    if (!overflowed()) {
      for (int k = 0; k < count; ++k) f(grid->points[index[k]], index[k]);
    } else {
      grid->for_each_covering(center, [&](vec3 p, float, int i) { f(p, i); });
    }
  }

  // f(p, w, 1/h², m) for every sample again, in the same order.
  template <class F>
  PSS_HOST_DEVICE void for_each(F&& f) const {
    for_each_sample([&](vec3 p, int i) {
      const float q = grid->inv_h2[i];
      const float m = grid->mass_of(i);
      f(p, m * gaussian_weight(length2(p - center), q), q, m);
    });
  }

  PSS_HOST_DEVICE WeightedMoments moments() const {
    WeightedMoments m(center);
    for_each([&](vec3 p, float w, float q, float) {
      m.add(p, w);
      m.inv_h2_sum += w * q;
    });
    return m;
  }

  PSS_HOST_DEVICE PolynomialFit polynomial_fit(const Frame& frame, bool weights_at_origin, float scale) const {
    PolynomialFit fit(scale);
    for_each([&](vec3 p, float w_r, float q, float m) {
      const vec3 l = frame.to_local(p);
      fit.add(l, weights_at_origin ? m * gaussian_weight(length2(l), q) : w_r);
    });
    return fit;
  }
};

// The local width h(r) of a neighbourhood from its moments: 1/√(Σw·h_i⁻²/Σw), the samples'
// widths averaged with their weights at r as 1/h² (what they store); with one global h, that
// h. It sizes what the projection measures in h: the line search's bracket, its tolerance,
// the polynomial's scale.
PSS_INLINE float local_width(const WeightedMoments& m) {
  return m.inv_h2_sum > 0 ? sqrt(m.weight_sum / m.inv_h2_sum) : 0.0f;
}

// ρ = 2h around the default h holds ~60 samples (points/spacing.hpp); 128 covers uneven
// sampling without walking the grid again in most places. The GPU keeps up to 96 indices
// (above), what fits the budget beside the ray's BVH stack (1,064 bytes of stack with 128);
// an earlier GPU build that kept the CPU's offsets and weights took 2.2–2.8 KB per thread.
#ifndef PSS_DEVICE_NEIGHBOURS
#define PSS_DEVICE_NEIGHBOURS 96
#endif
#if defined(__CUDA_ARCH__)
using Neighbourhood = NeighbourIndicesOf<PSS_DEVICE_NEIGHBOURS>;
using SampleIndices = Neighbourhood;
#else
using Neighbourhood = NeighbourhoodOf<128>;
// What APSS and RIMLS gather: they read each sample's normal and weigh it from points other
// than r, so the samples' indices serve them better than offsets and weights from r.
using SampleIndices = NeighbourIndicesOf<128>;
#endif

}  // namespace pss
