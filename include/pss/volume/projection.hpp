// The paper's projection of a point r onto the PSS of a volume (§4, §5.1): the predictor
// (Eq. 3, WLS with the feature weights θ) gives P(r), the corrector (Eq. 4, MLS-like with
// Θ = α1·θ + α2·θ3) refines it to γ. Neighbourhoods are the voxels around a point: no
// spatial search.
#pragma once

#include "pss/core/frame.hpp"
#include "pss/fit/brent.hpp"
#include "pss/fit/inverse_power.hpp"
#include "pss/fit/polynomial.hpp"
#include "pss/fit/weights.hpp"
#include "pss/volume/fields.hpp"
#include "pss/volume/voxel_gather_avx2.hpp"

namespace pss {

enum class VolumeMethod : unsigned char { predictor, predictor_corrector };

// Lengths in world units; VolumeParams::from_voxels gives the documented defaults.
struct VolumeParams {
  VolumeMethod method = VolumeMethod::predictor_corrector;
  float h = 0;             // θ3's width
  float radius = 0;        // of the neighbourhoods N(·): the voxels within it
  float step = 0;          // b = k·h, the marching step and the radius of the ball of trust
  float alpha = 0.9f;      // α1 of Eq. 4 (α2 = 1 − α1)
  float epsilon = 0;       // ε: r is a hit when |γ − r| ≤ ε
  float t_tolerance = 0;   // the t iterations stop when t moves less than this
  int max_predictor_iterations = 8;
  int max_corrector_iterations = 4;
  int max_retries = 6;     // projections from ray/polynomial intersections per sample
  bool debug_projection = false;  // record the first projection's moves (the paper's Figure 2)

  // How far a hit may stand off the data's own surface along its normal (surface_cells.hpp):
  // the PSS smooths at the scale h; 0.75h takes noise of a fifth of the contrast per voxel.
  PSS_HOST_DEVICE float surface_reach() const { return 0.75f * h; }
  // How far from a crossed cell a ray's sample is projected: samples are b apart, so every
  // crossing of a ray has one within b/2 (prepare_volume, surface_cells.hpp).
  PSS_HOST_DEVICE float sample_reach() const { return 0.5f * step; }

  // Defaults in voxel units u (VolumeView::voxel_size), see docs/paper-notes.md: h = 2u,
  // k = 0.75 (b = 1.5u), neighbourhood radius 1.5h, ε = 0.1u, α1 = 0.9; t iterations stop
  // below ε/2, a change that cannot decide an acceptance by itself.
  static VolumeParams from_voxels(float voxel, VolumeMethod method = VolumeMethod::predictor_corrector,
                                  float h_voxels = 2.0f, float k = 0.75f, float alpha = 0.9f,
                                  float epsilon_voxels = 0.1f, float radius_voxels = 3.0f) {
    VolumeParams p;
    p.method = method;
    p.h = h_voxels * voxel;
    p.radius = radius_voxels * voxel;
    p.step = k * p.h;
    p.alpha = alpha;
    p.epsilon = epsilon_voxels * voxel;
    p.t_tolerance = 0.5f * p.epsilon;
    return p;
  }
};

enum class VolumeProjectionStatus : unsigned char {
  ok,
  no_gradient,  // ∇f(r) = 0: no starting normal
  no_weight,    // no voxel near r carries feature weight
  beyond_curvature,  // the frame's origin lies beyond the polynomial's centre of curvature
};

struct VolumeProjection {
  vec3 predicted;  // P(r)
  vec3 point;      // γ (= P(r) for the predictor alone)
  vec3 normal;     // of the final polynomial's graph at `point`, along ∇f
  Frame frame;     // of the final polynomial
  Polynomial polynomial;
  VolumeProjectionStatus status;
  bool stopped_early = false;  // the predictor stopped at stop_beyond (Predictor): not the paper's P(r)
};

// One row of the lattice's box around a ball: voxels i0…i1 of row (j, k), the first at
// `index`, all at the offsets dy, dz from the ball's centre (dyz = dy² + dz² in the
// lattice's metric, VolumeView::metric).
struct VoxelRow {
  float dy, dz, dyz;
  int i0, i1;
  std::int64_t index;
};

// Calls row(VoxelRow) for the rows of the lattice's box around the ball B(x, radius) whose
// line meets the ball, in the lattice's order. The ball is round in the lattice's metric:
// on a grid of unequal spacing, an ellipsoid in space.
template <class F>
PSS_HOST_DEVICE void for_each_voxel_row_near(const VolumeView& v, vec3 x, float radius, F&& row) {
  const vec3 m = v.metric();
  const vec3 lo = v.to_grid(x - radius / m), hi = v.to_grid(x + radius / m);
  const int i0 = max(-int(floor(-lo.x)), 0), i1 = min(int(floor(hi.x)), v.dims.x - 1);
  const int j0 = max(-int(floor(-lo.y)), 0), j1 = min(int(floor(hi.y)), v.dims.y - 1);
  const int k0 = max(-int(floor(-lo.z)), 0), k1 = min(int(floor(hi.z)), v.dims.z - 1);
  const float r2 = radius * radius;
  for (int k = k0; k <= k1; ++k) {
    const float dz = v.origin.z + float(k) * v.spacing.z - x.z, mz = dz * m.z;
    for (int j = j0; j <= j1; ++j) {
      const float dy = v.origin.y + float(j) * v.spacing.y - x.y, my = dy * m.y;
      const float dyz = my * my + mz * mz;
      if (dyz > r2 || i0 > i1) continue;
      row(VoxelRow{dy, dz, dyz, i0, i1, v.index(i0, j, k)});
    }
  }
}

// Calls f(p − x, voxel index) for the voxels p within `radius` of x in the lattice's metric,
// in the lattice's order.
template <class F>
PSS_HOST_DEVICE void for_each_voxel_near(const VolumeView& v, vec3 x, float radius, F&& f) {
  const float r2 = radius * radius, mx = v.metric().x;
  for_each_voxel_row_near(v, x, radius, [&](const VoxelRow& row) {
    // (Cutting the row to the ball's chord made engine frames 20 % slower: the row's
    // sqrt and divisions cost more than the few voxel tests they spare.)
    std::int64_t index = row.index;
    for (int i = row.i0; i <= row.i1; ++i, ++index) {
      const float dx = v.origin.x + float(i) * v.spacing.x - x.x;
      if ((dx * mx) * (dx * mx) + row.dyz <= r2) f(vec3(dx, row.dy, row.dz), index);
    }
  });
}

// N(x): the voxels within the radius ρ of x, gathered once into a flat array (offsets from
// x, feature weights) so that the iterations of Eq. 3 and 4 and Brent's evaluations run
// over contiguous memory. Membership is smooth: each voxel counts with the window
// (1 − d²/ρ²)², which falls to zero at ρ, so that the projection changes continuously as
// the point moves and voxels enter or leave N (a hard edge shows the lattice in the
// shading and stalls the ray's fixed-point iteration; the paper does not say how far
// "the neighbouring voxels" reach). The capacity bounds ρ (neighbourhood_bound): a ball of
// radius 9 voxels (h = 6 voxels at the default radius 1.5h, for noisy scans), 80 KB of a CPU
// thread's stack, of which a projection touches only what it gathers. (It was 512, h ≤ 2.6
// voxels; walking the lattice at each pass instead, as the GPU does, took 3.7× as long on
// the tooth with h = 3.) Beyond it every pass of every projection would be long: refused.
inline constexpr int kMaxNeighbours = 4096;

// Whether a voxel at offset d from the centre counts, and with which weights: the window
// (1 − d²/ρ²)², d measured in the lattice's metric, and θ (θ1 or θ2 times the window and
// the facing). θ counts a voxel only as far as its gradient faces the way of n, the surface
// being fitted: the two faces of a wall thinner than the ball are sheets of opposite
// orientation, and a fit over both would settle between them. With `weighted_only` (the predictor, whose sums all carry θ), voxels whose
// windowed θ is below 1e-5 are left out: they could not move any sum by more than that fraction.
struct VoxelWeights {
  float inv_r2;
  vec3 n;
  bool weighted_only;
  vec3 metric;  // VolumeView::metric

  // 1 for a gradient within 60° of n, falling linearly to 0 at 90° and beyond: continuous,
  // so that the fit changes smoothly as n turns. `direction` is ∇f/|∇f|, or 0 where ∇f = 0.
  PSS_HOST_DEVICE static float facing(vec3 direction, vec3 n) {
    // Plain comparisons: clamp's fminf/fmaxf are library calls here, and NaN cannot occur.
    const float f = 2.0f * glm::dot(direction, n);
    return f < 0.0f ? 0.0f : (f > 1.0f ? 1.0f : f);
  }
  PSS_HOST_DEVICE bool operator()(const FieldView& fields, vec3 d, std::int64_t index, float& window, float& theta) const {
    const float u = 1.0f - length2(d * metric) * inv_r2;
    window = u * u;
    const FeatureVoxel voxel = fields.features[index];
    const float weighted = window * voxel.weight;
    if (weighted_only && weighted < 1e-5f) return false;  // facing ≤ 1
    theta = weighted * facing(voxel.direction, n);
    return !(weighted_only && theta < 1e-5f);
  }
};

// N(x) gathered once into flat arrays, one per coordinate: the iterations of Eq. 3 and 4
// and Brent's evaluations then sum over contiguous memory, in PSS_SUM_LANES lanes (SIMD on
// the CPU). The slots after the last voxel, up to a multiple of the lanes, hold zeros.
struct VoxelNeighbourhood {
  static constexpr int kSlots = kMaxNeighbours + PSS_SUM_LANES;
  vec3 center{0.0f};
  int count = 0;
  float dx[kSlots], dy[kSlots], dz[kSlots];  // pᵢ − center
  float window[kSlots];                      // (1 − dᵢ²/ρ²)²
  float theta[kSlots];                       // θ1 or θ2 of pᵢ, times the window and the facing

  PSS_HOST_DEVICE void gather(const FieldView& fields, vec3 c, float radius, vec3 n, bool weighted_only) {
    center = c;
    count = 0;
    const VoxelWeights weights{1.0f / (radius * radius), n, weighted_only, fields.volume.metric()};
#if PSS_CPU_AVX2
    if (cpu::has_avx2()) {
      gather_rows_avx2(fields, radius, weights);
    } else
#endif
    {
      for_each_voxel_near(fields.volume, c, radius, [&](vec3 d, std::int64_t index) { add(fields, weights, d, index); });
    }
    pad();
  }
  // The same N(x) by the scalar walk alone: what the GPU and CPUs without AVX2 run (tests
  // compare both ways with a brute-force loop on any CPU).
  PSS_HOST_DEVICE void gather_scalar(const FieldView& fields, vec3 c, float radius, vec3 n, bool weighted_only) {
    center = c;
    count = 0;
    const VoxelWeights weights{1.0f / (radius * radius), n, weighted_only, fields.volume.metric()};
    for_each_voxel_near(fields.volume, c, radius, [&](vec3 d, std::int64_t index) { add(fields, weights, d, index); });
    pad();
  }
  PSS_HOST_DEVICE vec3 offset(int i) const { return vec3(dx[i], dy[i], dz[i]); }

 private:
  PSS_HOST_DEVICE void pad() {
    for (int i = count; i % PSS_SUM_LANES != 0; ++i) dx[i] = dy[i] = dz[i] = window[i] = theta[i] = 0;
  }
  // Stores the voxel at offset d if it counts, while there is room (the first kMaxNeighbours
  // in the lattice's order).
  PSS_HOST_DEVICE void add(const FieldView& fields, const VoxelWeights& weights, vec3 d, std::int64_t index) {
    if (count == kMaxNeighbours) return;
    float w, t;
    if (!weights(fields, d, index, w, t)) return;
    dx[count] = d.x;
    dy[count] = d.y;
    dz[count] = d.z;
    window[count] = w;
    theta[count] = t;
    ++count;
  }
#if PSS_CPU_AVX2
  // The same voxels, eight of a row at a time (volume/voxel_gather_avx2.hpp); the last
  // voxels of the array, where 8 could not be read, one at a time.
  void gather_rows_avx2(const FieldView& fields, float radius, const VoxelWeights& weights) {
    const VolumeView& v = fields.volume;
    const std::int64_t voxels = std::int64_t(v.dims.x) * v.dims.y * v.dims.z;
    const float r2 = radius * radius;
    static_assert(kSlots >= kMaxNeighbours + 8, "a row's 8 lanes are stored at count < kMaxNeighbours");
    const detail::GatherSlots slots{dx, dy, dz, window, theta};
    for_each_voxel_row_near(v, center, radius, [&](const VoxelRow& row) {
      for (int i = row.i0; i <= row.i1 && count < kMaxNeighbours; i += 8) {
        const std::int64_t index = row.index + (i - row.i0);
        const int lanes = min(row.i1 - i + 1, 8);
        if (index + 8 <= voxels) {
          count += detail::gather_row_avx2(fields.features, index, i, lanes, v.origin.x, v.spacing.x, center.x,
                                           weights.metric.x, row.dy, row.dz, row.dyz, r2, weights.inv_r2, weights.n,
                                           weights.weighted_only, count, slots);
          count = min(count, kMaxNeighbours);
          continue;
        }
        for (int l = 0; l < lanes; ++l) {
          const float x = v.origin.x + float(i + l) * v.spacing.x - center.x, mx = x * weights.metric.x;
          if (mx * mx + row.dyz <= r2) add(fields, weights, vec3(x, row.dy, row.dz), index + l);
        }
      }
    });
  }
#endif

 public:
  // f(pᵢ − center, window, θ) for each voxel of N, in the lattice's order.
  template <class F>
  PSS_HOST_DEVICE void for_each(F&& f) const {
    for (int i = 0; i < count; ++i) f(offset(i), window[i], theta[i]);
  }
  // out[k] = Σᵢ term(pᵢ − center, window, θ)[k]; term must give 0 where window and θ are 0.
  template <int K, class Term>
  PSS_HOST_DEVICE void sum(float (&out)[K], Term&& term) const {
    constexpr int L = PSS_SUM_LANES;
    float lanes[K][L] = {};
    for (int i0 = 0; i0 < count; i0 += L) {
      for (int l = 0; l < L; ++l) {
        float terms[K];
        term(offset(i0 + l), window[i0 + l], theta[i0 + l], terms);
        for (int k = 0; k < K; ++k) lanes[k][l] += terms[k];
      }
    }
    for (int k = 0; k < K; ++k) {
      out[k] = 0;
      for (int l = 0; l < L; ++l) out[k] += lanes[k][l];
    }
  }
  // Σw, Σw·d, Σw·d·dᵀ with w = weight(d, window, θ) (0 where window and θ are 0).
  template <class W>
  PSS_HOST_DEVICE WeightedMoments moments(W&& weight) const {
    WeightedMoments m(center);
    m.add_all(count, [&](int i) { return offset(i); }, [&](int i) { return weight(offset(i), window[i], theta[i]); });
    return m;
  }
  // The polynomial's normal equations in `frame` with those weights.
  template <class W>
  PSS_HOST_DEVICE PolynomialFit polynomial_fit(const Frame& frame, float h, W&& weight) const {
    PolynomialFit fit(h);
    const vec3 o = frame.to_local(center);
    fit.add_all(count, [&](int i) { return o + frame.direction_to_local(offset(i)); },
                [&](int i) { return weight(offset(i), window[i], theta[i]); });
    return fit;
  }
};

// The same N(x) walked on the lattice again at each pass instead of stored: a few registers
// instead of 20 bytes a voxel of stack per GPU thread. The same voxels in the same order.
struct WalkedVoxelNeighbourhood {
  const FieldView* fields = nullptr;
  vec3 center;
  float radius = 0;
  VoxelWeights weights{};

  PSS_HOST_DEVICE void gather(const FieldView& f, vec3 c, float r, vec3 n, bool weighted_only) {
    fields = &f;
    center = c;
    radius = r;
    weights = VoxelWeights{1.0f / (r * r), n, weighted_only, f.volume.metric()};
  }
  template <class F>
  PSS_HOST_DEVICE void for_each(F&& f) const {
    for_each_voxel_near(fields->volume, center, radius, [&](vec3 d, std::int64_t index) {
      float w, t;
      if (weights(*fields, d, index, w, t)) f(d, w, t);
    });
  }
  template <int K, class Term>
  PSS_HOST_DEVICE void sum(float (&out)[K], Term&& term) const {
    for (int k = 0; k < K; ++k) out[k] = 0;
    for_each([&](vec3 d, float window, float theta) {
      float terms[K];
      term(d, window, theta, terms);
      for (int k = 0; k < K; ++k) out[k] += terms[k];
    });
  }
  template <class W>
  PSS_HOST_DEVICE WeightedMoments moments(W&& weight) const {
    WeightedMoments m(center);
    for_each([&](vec3 d, float window, float theta) { m.add_offset(d, weight(d, window, theta)); });
    return m;
  }
  template <class W>
  PSS_HOST_DEVICE PolynomialFit polynomial_fit(const Frame& frame, float h, W&& weight) const {
    PolynomialFit fit(h);
    const vec3 o = frame.to_local(center);
    for_each([&](vec3 d, float window, float theta) { fit.add(o + frame.direction_to_local(d), weight(d, window, theta)); });
    return fit;
  }
};

// The kernels' scratch space. The GPU walks the lattice at each pass: a stored N(x) takes
// 20 bytes a voxel per thread (80 KB), in local memory, against a budget of 1 KiB
// (tests/gpu/kernel_stacks.py). (An earlier GPU build stored 512 voxels; walking measured
// 1.6–2× slower predictor-corrector frames on an H100 then, docs/benchmarks.md, a cost to
// measure again with the stack budget.)
#if defined(__CUDA_ARCH__)
using VoxelScratch = WalkedVoxelNeighbourhood;
#else
using VoxelScratch = VoxelNeighbourhood;
#endif

// The most voxels a ball of this radius can hold on this grid, for the host's check: each
// voxel's cell lies in the ball grown by half a cell diagonal. In lattice steps the ball's
// semi-axes are radius/u along every axis (VolumeView::metric).
PSS_INLINE float neighbourhood_bound(float radius, const VolumeView& v) {
  const float r = radius / v.voxel_size() + 0.87f;
  return 4.18879f * r * r * r;
}

// Inverse power steps per normal update: each starts from the previous n, and the outer
// iterations of Eq. 3 and 4 go on refining it.
inline constexpr int kEigenIterations = 4;

// The normal of the plane that fits the covariance C = Σw·dᵢdᵢᵀ / Σw best, starting from n:
// the smallest eigenvector of C measured in the lattice's metric M (VolumeView::metric), MCM,
// taken back to space (the plane n'·Mx = c has the normal Mn'). On a grid of unequal spacing
// the neighbourhood is long along the coarse axis, and the plain C's smallest eigenvector
// would lie across it whatever the surface (a ball's mesh then had normals 26° off).
// Unchanged where the eigenvector is invalid.
PSS_INLINE vec3 plane_normal(const Sym3& c, vec3 n, vec3 metric) {
  if (metric == vec3(1.0f)) {
    const EigenResult eig = smallest_eigenvector(c, n, kEigenIterations);
    return eig.status == EigenStatus::invalid ? n : eig.vector;
  }
  const vec3 m = metric;
  const Sym3 mcm{c.xx * m.x * m.x, c.xy * m.x * m.y, c.xz * m.x * m.z, c.yy * m.y * m.y, c.yz * m.y * m.z,
                 c.zz * m.z * m.z};
  const EigenResult eig = smallest_eigenvector(mcm, glm::normalize(n / m), kEigenIterations);
  return eig.status == EigenStatus::invalid ? n : glm::normalize(m * eig.vector);
}

namespace detail {

// Eq. 4's energy along n for fixed n about x0 = P(r): E(t) = Σ Θᵢ(t)·⟨n, pᵢ − (x0 + t·n)⟩²,
// Θᵢ(t) = α1·θᵢ + α2·θ3(‖pᵢ − (x0 + t·n)‖), with its derivative for Brent. θ3's distance is
// the lattice's metric M (VolumeView::metric): with dᵢ = pᵢ − x0, zᵢ = ⟨n, dᵢ⟩, sᵢ = zᵢ − t,
// ‖M(dᵢ − t·n)‖² = ‖Mdᵢ‖² − 2t·⟨Mdᵢ, Mn⟩ + t²‖Mn‖², so dθ3/dt = 2(⟨Mdᵢ, Mn⟩ − t‖Mn‖²)θ3/h²
// (2sᵢθ3/h² on a cubic grid, M = 1). Both parts of Θ carry the neighbourhood's window.
template <class Nb>
struct CorrectorEnergy {
  const Nb& nb;
  vec3 n;
  float h, alpha;
  vec3 metric;

  PSS_HOST_DEVICE float operator()(float t, float& derivative) const {
    const float inv_h2 = 1.0f / (h * h);
    const vec3 mn = n * metric;
    const float mn2 = metric == vec3(1.0f) ? 1.0f : length2(mn);  // n is a unit vector
    float sums[2];
    nb.sum(sums, [&](vec3 d, float window, float theta, float (&terms)[2]) {
      const vec3 md = d * metric;
      const float s = glm::dot(d, n) - t, along = glm::dot(md, mn) - t * mn2;
      const float theta3 = window * exp_nonpositive(-(length2(md) - 2 * t * glm::dot(md, mn) + t * t * mn2) * inv_h2);
      const float w = alpha * theta + (1 - alpha) * theta3;
      terms[0] = w * s * s;
      terms[1] = (1 - alpha) * 2 * along * theta3 * inv_h2 * s * s - 2 * w * s;
    });
    derivative = sums[1];
    return sums[0];
  }
};

// Eq. 4's weight Θᵢ = α1·θᵢ + α2·θ3(‖pᵢ − c‖) with c = `center` (relative to the
// neighbourhood's centre) and the distance in the lattice's metric, the window carried by
// both parts: the corrector's covariance and polynomial weight their voxels so.
struct CorrectorWeight {
  float alpha, inv_h2;
  vec3 center, metric;
  PSS_HOST_DEVICE float operator()(vec3 d, float window, float theta) const {
    return alpha * theta + (1 - alpha) * window * exp_nonpositive(-length2((d - center) * metric) * inv_h2);
  }
};

// The polynomial in the frame (origin, n) fitted with weights weight(d, window, θ) over the
// neighbourhood, and the orthogonal projection of the origin onto its graph
// (project_origin_onto_graph).
template <class Nb, class W>
PSS_HOST_DEVICE VolumeProjection fit_and_project(const Nb& nb, vec3 origin, vec3 n, float h, W&& weight) {
  VolumeProjection out;
  out.frame = Frame::from_normal(origin, n);
  out.polynomial = nb.polynomial_fit(out.frame, h, weight).solve();
  vec3 local;
  const bool projected = project_origin_onto_graph(out.polynomial, local);
  out.point = out.frame.to_world(local);
  out.normal = out.frame.direction_to_world(out.polynomial.normal(local.x, local.y));
  out.status = projected ? VolumeProjectionStatus::ok : VolumeProjectionStatus::beyond_curvature;
  return out;
}

}  // namespace detail

// Predictor (§5.1, Eq. 3). n starts as ∇f/|∇f| at r; then, alternately, t minimises Eq. 3
// for fixed n (a weighted mean along n) and n becomes the smallest eigenvector of
// C1(q) = Σ θᵢ(pᵢ − q)(pᵢ − q)ᵀ, q = r + t·n, until t moves less than the tolerance. Each
// iteration gathers N(·) once, around the q of the previous iteration, and shifts the
// moments to the new q; at convergence that is the paper's N(q). The polynomial is fitted
// with θ in the frame of H(n, q), and P(r) is q's orthogonal projection onto it.
//
// Resumable: a caller that wants P(r) only for where its polynomial meets a ray may stop
// the iterations once q is farther than `stop_beyond` from r (marcher.hpp). The result is
// then marked `stopped_early`, its polynomial from the last gather, and run() again (only
// after such a result) resumes the iterations where they stopped: it ends where one
// uninterrupted run ends, up to the rounding of the code around each call.
template <class Nb>
struct Predictor {
  const FieldView* fields;
  vec3 r, n{0, 0, 1};
  float t = 0;
  int iteration = 0;
  bool has_gradient;  // ∇f(r) ≠ 0: n starts along it

  PSS_HOST_DEVICE Predictor(const FieldView& f, vec3 point) : fields(&f), r(point) {
    const vec3 g = f.gradient_at(r);
    has_gradient = length2(g) > 0;
    if (has_gradient) n = g / glm::length(g);
  }

  PSS_HOST_DEVICE VolumeProjection run(const VolumeParams& params, Nb& nb, float stop_beyond = kInfinity) {
    VolumeProjection fail;
    fail.predicted = fail.point = r;
    fail.normal = vec3(0, 0, 1);
    fail.frame = Frame::from_normal(r, fail.normal);
    fail.status = has_gradient ? VolumeProjectionStatus::no_weight : VolumeProjectionStatus::no_gradient;
    if (!has_gradient) return fail;
    const auto theta_of = [](vec3, float, float theta) { return theta; };
    bool stopped_early = false;
    while (iteration < params.max_predictor_iterations) {
      ++iteration;
      nb.gather(*fields, r + t * n, params.radius, n, true);
      const WeightedMoments moments = nb.moments(theta_of);
      const float w = moments.weight_sum;
      const vec3 m = moments.first;  // Σθ(pᵢ − q)
      Sym3 c = moments.second;       // Σθ(pᵢ − q)(pᵢ − q)ᵀ
      if (!(w > 0)) return fail;
      // Eq. 3 for fixed n: t = Σθ⟨n, pᵢ − r⟩ / Σθ.
      const float dt = glm::dot(m, n) / w;
      // C1 about q + δ from the moments about q: C − mδᵀ − δmᵀ + Wδδᵀ.
      const vec3 delta = dt * n;
      c.add_outer(delta, w);
      c.xx -= 2 * m.x * delta.x;
      c.yy -= 2 * m.y * delta.y;
      c.zz -= 2 * m.z * delta.z;
      c.xy -= m.x * delta.y + m.y * delta.x;
      c.xz -= m.x * delta.z + m.z * delta.x;
      c.yz -= m.y * delta.z + m.z * delta.y;
      t += dt;
      n = plane_normal(c.scaled(1.0f / w), n, fields->volume.metric());
      if (abs(dt) < params.t_tolerance) break;
      if (abs(t) > stop_beyond && iteration < params.max_predictor_iterations) {
        stopped_early = true;
        break;
      }
    }
    VolumeProjection out = detail::fit_and_project(nb, r + t * n, n, params.h, theta_of);
    out.predicted = out.point;
    out.stopped_early = stopped_early;
    return out;
  }
};

template <class Nb>
PSS_HOST_DEVICE VolumeProjection predict(const FieldView& fields, const VolumeParams& params, vec3 r, Nb& nb) {
  return Predictor<Nb>(fields, r).run(params, nb);
}

// Corrector (§5.1, Eq. 4) from x0 = P(r) with the predictor's n: t minimises Eq. 4 by Brent
// with derivatives, then n becomes the smallest eigenvector of C2(x0) = Σ Θᵢ(pᵢ − x0)(pᵢ − x0)ᵀ
// over N(x0), until t settles. The polynomial is fitted with Θ in the frame (x0, n), and γ
// is x0's orthogonal projection onto it.
template <class Nb>
PSS_HOST_DEVICE VolumeProjection correct(const FieldView& fields, const VolumeParams& params,
                                         const VolumeProjection& predicted, Nb& nb) {
  const vec3 x0 = predicted.point;
  vec3 n = predicted.frame.n;
  const float h = params.h, alpha = params.alpha;
  const float inv_h2 = 1.0f / (h * h);
  const vec3 metric = fields.volume.metric();
  nb.gather(fields, x0, params.radius, n, false);
  float t = 0;
  for (int it = 0; it < params.max_corrector_iterations; ++it) {
    const detail::CorrectorEnergy<Nb> energy{nb, n, h, alpha, metric};
    // Brent searches t ± h from the minimiser of the α1 part alone (a θ-weighted mean of
    // the heights, closed form), which is where the α2 part only nudges it.
    float sums[2];
    nb.sum(sums, [&](vec3 d, float, float theta, float (&terms)[2]) {
      terms[0] = theta;
      terms[1] = theta * glm::dot(d, n);
    });
    const float w = sums[0], wz = sums[1];
    const float start = w > 0 ? clamp(wz / w, t - h, t + h) : t;
    const float t_next = brent_minimize(energy, t - h, t + h, start, params.t_tolerance).x;
    const WeightedMoments moments = nb.moments(detail::CorrectorWeight{alpha, inv_h2, t_next * n, metric});
    const Sym3 c = moments.second;
    const float weight_sum = moments.weight_sum;
    if (weight_sum > 0) n = plane_normal(c.scaled(1.0f / weight_sum), n, metric);
    const bool settled = abs(t_next - t) < params.t_tolerance;
    t = t_next;
    if (settled) break;
  }
  VolumeProjection out = detail::fit_and_project(nb, x0, n, h, detail::CorrectorWeight{alpha, inv_h2, t * n, metric});
  out.predicted = predicted.point;
  return out;
}

// P(r) alone or followed by the corrector, as the method asks.
// `nb` is scratch space, the caller's so that a loop of projections reuses it.
template <class Nb>
PSS_HOST_DEVICE VolumeProjection project_volume_point(const FieldView& fields, const VolumeParams& params, vec3 r,
                                                      Nb& nb) {
  const VolumeProjection p = predict(fields, params, r, nb);
  if (p.status != VolumeProjectionStatus::ok || params.method == VolumeMethod::predictor) return p;
  return correct(fields, params, p, nb);
}

}  // namespace pss
