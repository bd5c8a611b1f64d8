// The PSS projection operator P(r) of a point cloud (paper §3): a local plane H(n, q),
// q = r + t·n, by WLS (Eq. 1) or MLS (Eq. 2); the polynomial g(x, y) fitted by WLS on it;
// P(r) = q + g(0, 0)·n. Every sum runs over N(r), the samples within ρ of r; with adaptive
// support each sample has its own h_i and ρ_i, and N(r) holds those within their ρ_i of r
// (spatial/support_grid.hpp).
#pragma once

#include <string_view>

#include "pss/core/frame.hpp"
#include "pss/fit/brent.hpp"
#include "pss/fit/inverse_power.hpp"
#include "pss/fit/polynomial.hpp"
#include "pss/fit/weights.hpp"
#include "pss/points/neighbourhood.hpp"
#include "pss/spatial/uniform_grid.hpp"

namespace pss {

enum class PlaneFitMethod : unsigned char { wls, mls };

// The numbers are a file format: `pss project` writes them as the PLY property 'status'.
enum class ProjectionStatus : unsigned char {
  converged = 0,
  not_converged = 1,       // MLS alternation still moving after max_mls_iterations
  too_few_neighbours = 2,  // fewer than 3 samples in N(r): no plane; point and normal unchanged
  degenerate_normal = 3,   // neighbours (nearly) on a line: the normal is the start vector's
};

// How wide each sample's weight is (issue 26): one h for every sample, as the paper, or h_i
// growing with the distance to its k-th nearest neighbour where the cloud is sparser than
// its median by more than 4/3 (points/support.hpp), so that a cloud whose spacing varies is not torn where it
// is sparse. Lengths given at h (ρ, the tolerances, the ray tracer's b, ε, δ) then scale
// with h_i/h.
enum class Support : unsigned char { global, adaptive };

// The surface a cloud defines (issue 26): the paper's MLS plane and polynomial, or an
// algebraic sphere fitted to the samples and their normals (APSS, points/algebraic_sphere.hpp),
// or the robust implicit MLS that keeps creases and thin parts (RIMLS,
// points/robust_implicit.hpp). The last two read the samples' oriented normals
// (points/sample_normals.hpp) and are dispatched by points/surface_projection.hpp.
enum class SurfaceOperator : unsigned char { mls, apss, rimls };

inline const char* surface_name(SurfaceOperator s) {
  return s == SurfaceOperator::apss ? "apss" : s == SurfaceOperator::rimls ? "rimls" : "mls";
}
// surface_name's inverse; a name it does not give is MLS (callers check the name first).
inline SurfaceOperator surface_operator_of(std::string_view name) {
  return name == "apss" ? SurfaceOperator::apss : name == "rimls" ? SurfaceOperator::rimls : SurfaceOperator::mls;
}

// Where the samples' normals come from: the file's, when it has them (hints of MLS's
// orientation, what APSS and RIMLS fit), or estimated from the points and oriented
// consistently, the file's ignored (`--normals file|estimate`).
enum class NormalSource : unsigned char { file, estimate };

// Whether the samples off the surface the others define are set aside before any fit
// (points/outliers.hpp, `--outliers set-aside|keep`).
enum class OutlierPolicy : unsigned char { set_aside, keep };

// Whether the surface ends at its samples (points/borders.hpp: what the ray tracer shows,
// `--borders clip`) or runs on past the last of them as the projection extrapolates (the
// paper; what `pss project` computes for any point given).
enum class BorderMode : unsigned char { clip, extend };

inline const char* border_name(BorderMode m) { return m == BorderMode::clip ? "clip" : "extend"; }

// The most MLS alternations, or APSS's and RIMLS's fits, per projection by default. MLS: 4;
// more let t wander past the data (Amenta and Kil's spurious minima): `pss mesh` of the bunny
// opened from 784 to 1,080 boundary edges at 8. APSS and RIMLS: 8; where the noise sets h
// (3σ), each fit's move is only a few times shorter than the last, and at 4, 17 % of a noisy
// sphere's projections were still moving (docs/paper-notes.md).
inline int default_iterations(SurfaceOperator s) { return s == SurfaceOperator::mls ? 4 : 8; }

struct ProjectionParams {
  float h = 0;    // Gaussian width of θ3, the local level of detail (with adaptive support, the least h_i)
  float rho = 0;  // range-query radius, 2h in the paper
  PlaneFitMethod plane = PlaneFitMethod::mls;
  Support support = Support::global;
  SurfaceOperator surface = SurfaceOperator::mls;
  NormalSource normals = NormalSource::file;  // read on the host, before any kernel
  OutlierPolicy outliers = OutlierPolicy::set_aside;  // likewise
  BorderMode borders = BorderMode::extend;  // clip: Projection::surrounded is computed
  // The MLS alternations of t and n; for APSS and RIMLS, the fits moved to the last point
  // (with PlaneFitMethod::wls, one fit at r, as the ray tracer's loop takes). Defaults:
  // default_iterations.
  int max_mls_iterations = 4;
  float t_tolerance = 0;  // MLS stops when t moves less than this (default 1e-3·h), at h

  static ProjectionParams from_h(float h, PlaneFitMethod plane = PlaneFitMethod::mls) {
    ProjectionParams p;
    p.h = h;
    p.rho = 2 * h;
    p.plane = plane;
    p.t_tolerance = 1e-3f * h;
    return p;
  }
};

struct Projection {
  vec3 point;   // P(r)
  vec3 normal;  // n of the final plane: g has no linear terms, so this is also the normal
                // of the graph of g at P(r)
  Frame frame;  // at q, with n; g lives in it
  Polynomial polynomial;
  float t;
  int neighbours;
  ProjectionStatus status;
  bool surrounded = true;  // with BorderMode::clip, whether P(r) lies among its samples; true where not tested
};

// What a projection that cannot start returns: r itself, with the hint's normal (or +z).
PSS_INLINE Projection unprojected(vec3 r, vec3 normal_hint) {
  Projection out;
  out.point = r;
  out.normal = length2(normal_hint) > 0 ? glm::normalize(normal_hint) : vec3(0, 0, 1);
  out.t = 0;
  out.frame = Frame::from_normal(r, out.normal);
  out.neighbours = 0;
  out.status = ProjectionStatus::too_few_neighbours;
  return out;
}

// The projection of APSS and RIMLS, by fits moved along: from x = r, `steps` times (one
// for the ray tracer's loop, which iterates itself; more for `pss project`, until a step
// moves less than the tolerance), step(x, h, out) fits the surface at x over N(r)
// (`samples`, gathered at r), moves x onto it, sets out's normal, frame and polynomial there,
// and returns how far x moved, or a negative number where the fit has no surface
// (degenerate_normal). h is the local width h(r), which sizes the fits and the tolerance.
template <class Samples, class Step>
PSS_HOST_DEVICE Projection project_by_fits(const Samples& samples, vec3 r, const ProjectionParams& params,
                                           vec3 normal_hint, int steps, Step&& step) {
  Projection out = unprojected(r, normal_hint);
  out.neighbours = samples.count;
  if (samples.count < 3) return out;
  const float h = local_width(samples.moments());
  if (!(h > 0)) return out;
  const float tolerance = params.t_tolerance * (h / params.h);
  vec3 x = r;
  out.status = ProjectionStatus::not_converged;
  for (int k = 0; k < steps; ++k) {
    const float moved = step(x, h, out);
    if (!(moved >= 0)) {
      out.status = ProjectionStatus::degenerate_normal;
      out.point = r;
      return out;
    }
    if (steps == 1 || moved < tolerance) {
      out.status = ProjectionStatus::converged;
      break;
    }
  }
  out.point = x;
  out.t = glm::dot(x - r, out.normal);
  return out;
}

namespace detail {

// Eq. 2's energy along n for fixed n: E(t) = Σ θ3(‖pᵢ − q‖)·⟨pᵢ − q, n⟩², q = r + t·n,
// and its derivative, with zᵢ = ⟨pᵢ − r, n⟩ and ‖pᵢ − q‖² = ‖pᵢ − r‖² − 2t·zᵢ + t².
template <class Nb>
struct MlsEnergy {
  const Nb& neighbours;
  vec3 r, n;

  PSS_HOST_DEVICE float operator()(float t, float& derivative) const {
    float e = 0, de = 0;
    neighbours.for_each([&](vec3 p, float, float inv_h2, float m) {
      const float d2 = length2(p - r);
      const float z = glm::dot(p - r, n);
      const float s = z - t;
      const float w = m * exp_nonpositive(-(d2 - 2 * t * z + t * t) * inv_h2);  // inline: Brent calls it most
      e += w * s * s;
      de += w * s * 2 * (s * s * inv_h2 - 1);
    });
    derivative = de;
    return e;
  }
};

}  // namespace detail

// Nb is the neighbourhood's storage (neighbourhood.hpp); every capacity gives the same result.
// The grid holds the samples' widths; params' lengths are taken at params.h and scaled to
// the local width h(r) (local_width).
// project_mls is P(r) over N(r) gathered already (`neighbours`, centred at r), which every
// later pass reads again.
template <class Nb>
PSS_HOST_DEVICE Projection project_mls(const Nb& neighbours, vec3 r, const ProjectionParams& params,
                                       vec3 normal_hint) {
  Projection out = unprojected(r, normal_hint);

  // Eq. 1 with the weighter at r: for fixed weights the best plane passes through the
  // weighted mean m, its normal is the smallest eigenvector of the covariance about m.
  // N(r) is gathered once, with its weights θ3(‖pᵢ − r‖).
  const WeightedMoments moments = neighbours.moments();
  out.neighbours = moments.count;
  if (moments.count < 3 || !(moments.weight_sum > 0)) return out;
  const float h = local_width(moments);
  const float t_tolerance = params.t_tolerance * (h / params.h);

  // The hint itself, not unprojected()'s +z when there is none: a start vector orthogonal to
  // the normal never turns to it where the data are exactly planar (a CAD face x = const).
  EigenResult eig = smallest_eigenvector(moments.covariance_about_mean(), normal_hint);
  vec3 n = eig.vector;
  float t = glm::dot(moments.mean() - r, n);
  ProjectionStatus status = ProjectionStatus::converged;

  if (params.plane == PlaneFitMethod::mls) {
    // Eq. 2 by alternation: t along n by Brent with derivative, then n as the smallest
    // eigenvector of C(q) = Σ θ3(‖pᵢ − q‖)(pᵢ − q)(pᵢ − q)ᵀ, the plane through q.
    status = ProjectionStatus::not_converged;
    for (int it = 0; it < params.max_mls_iterations; ++it) {
      const detail::MlsEnergy<Nb> energy{neighbours, r, n};
      const float t_next = brent_minimize(energy, t - h, t + h, t, t_tolerance).x;
      const vec3 q = r + t_next * n;
      WeightedMoments at_q(q);
      neighbours.for_each(
          [&](vec3 p, float, float inv_h2, float m) { at_q.add(p, m * gaussian_weight(length2(p - q), inv_h2)); });
      eig = smallest_eigenvector(at_q.covariance_about_origin(), n);
      const float moved = abs(t_next - t) + h * glm::length(eig.vector - n);
      n = eig.vector;
      t = t_next;
      if (moved < t_tolerance) {
        status = ProjectionStatus::converged;
        break;
      }
    }
  }
  // No spread (samples that coincide: a zero covariance) defines no normal either.
  if (eig.status == EigenStatus::degenerate || eig.status == EigenStatus::invalid)
    status = ProjectionStatus::degenerate_normal;

  // The polynomial, weighted from r (WLS) or from q (MLS) like the plane, in the frame of
  // H(n, q).
  const vec3 q = r + t * n;
  const Frame frame = Frame::from_normal(q, n);
  out.polynomial = neighbours.polynomial_fit(frame, params.plane == PlaneFitMethod::mls, h).solve();
  out.frame = frame;
  out.t = t;
  out.point = q + out.polynomial.d * n;
  out.normal = n;
  out.status = status;
  return out;
}

}  // namespace pss
