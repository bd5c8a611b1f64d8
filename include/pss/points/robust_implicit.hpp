// RIMLS, robust implicit moving least squares (Öztireli, Guennebaud & Gross, Eurographics
// 2009), the projection of `--surface rimls`: the implicit surface f(x) = 0 of
//   f(x) = Σ wᵢ·(x − pᵢ)·nᵢ / Σ wᵢ,   wᵢ = αᵢ·θ3(‖x − pᵢ‖),
// each sample's tangent plane averaged with its weight, refitted with robust weights αᵢ
// that leave out the samples disagreeing with the fit: those whose plane lies far from f
// (an outlier; residual scale σ_r·hᵢ) and those whose normal differs from ∇f (the other face
// of a crease, the other sheet of a thin part; σ_n). Creases stay sharp and thin parts two
// sheets; a stray near the surface still bends it where it dominates the weights (that is
// points/outliers.hpp's). It needs oriented normals (grid.normals).
#pragma once

#include "pss/core/frame.hpp"
#include "pss/fit/weights.hpp"
#include "pss/points/projection.hpp"

namespace pss {

// The robust weights' scales: σ_n = 0.75, the sharpness MeshLab's RIMLS filter starts at
// (the paper uses 0.5 to 1.5); σ_r = 1 in units of each sample's h_i (the paper's σ_r of
// 0.5 to 2 in the units of the sample spacing). Three fits at most (the first unweighted),
// stopping once ∇f moves less than √1e-3 (as MeshLab).
inline constexpr float kRimlsSigmaN = 0.75f;
inline constexpr float kRimlsSigmaR = 1.0f;
inline constexpr int kRimlsFits = 3;

// The normals' agreement (cosine) from which a sample's plane is corrected for the surface's
// curvature in full, and below which not at all (fit_robust_implicit): about 30° and 45°.
inline constexpr float kRimlsCurvedFrom = 0.87f;
inline constexpr float kRimlsCreaseBelow = 0.7f;

// Whether fit_robust_implicit also filters the normal (below), or gives ∇f alone.
enum class ReportedNormal : unsigned char { filtered, gradient };

struct RobustImplicit {
  float f = 0;
  vec3 gradient{0.0f};
  float correction = 0;  // for the curvature: f + correction is the surface's distance
  bool valid = false;
};

// f and ∇f at x by Öztireli et al.'s Listing 1:
//   ∇f = (Σ wᵢnᵢ + Σ ∇wᵢ·((x − pᵢ)·nᵢ − f)) / Σ wᵢ,  ∇θ3 = −2(x − pᵢ)/hᵢ²·θ3,
// with f corrected for the curvature. Their f averages the samples' tangent planes, each of
// which a curved surface leaves by about ‖x − pᵢ‖²/2R: f = 0 lies off a surface of radius R
// by about ⟨‖x − pᵢ‖²⟩/2R (0.7 % R on a sphere of 4,000 samples at the default h). Averaged
// with the plane through pᵢ normal to n = ∇f/‖∇f‖ at x, each sample's term is
// (x − pᵢ)·(nᵢ + n)/2, on a sphere (|x|² − |pᵢ|²)/2R, zero at |x| = R: no bias. That average is
// taken where the normals agree as a smooth surface's do within a support (nᵢ·n above
// kRimlsCurvedFrom), and not across a crease (below kRimlsCreaseBelow), whose other face's
// planes would pull f off the face (docs/paper-notes.md). Each fit's sum takes n from the
// fit before it, so the correction is taken once the fits converge (∇f moved less than √1e-3,
// about 2° where ‖∇f‖ ≈ 1, as it is near the surface); a fit that does not converge within
// kRimlsFits keeps the paper's f.
// ∇f is the samples' mean normal m = Σ wᵢnᵢ / Σ wᵢ plus c = Σ ∇wᵢ·(fᵢ − f) / Σ wᵢ, a regression
// of the residuals on position: c turns m to the points where their normals lean, and carries
// the points' noise (on issue 27's noisy torus ∇f is 2° off, m 1°). With
// ReportedNormal::filtered, `normal` is set to m + s·c, s = clamp(1 − v/‖c‖², 0, 1), where
// v = Σ ‖∇wᵢ‖²(eᵢ − ē)² / (Σ wᵢ)² is the variance c would have if the samples' planes at x, eᵢ,
// scattered by noise alone (eᵢ corrected for the curvature as f is; ē their mean under
// ‖∇wᵢ‖²): an empirical Wiener filter, which keeps c where it stands out of the noise
// (normals that lean) and drops it where it does not (docs/paper-notes.md). `normal` is an
// out-parameter, not a member of RobustImplicit: as a member it put the GPU's secondary-ray
// kernel at 1,120 bytes of stack, over its budget of 1,024 (tests/gpu/kernel_stacks.py).
template <ReportedNormal reported, class Samples>
PSS_HOST_DEVICE RobustImplicit fit_robust_implicit(const Samples& samples, vec3 x, vec3& normal) {
  RobustImplicit fit;
  const float inv_sn2 = 1 / (kRimlsSigmaN * kRimlsSigmaN);
  const float inv_sr2 = 1 / (kRimlsSigmaR * kRimlsSigmaR);
  for (int k = 0; k < kRimlsFits; ++k) {
    float sw = 0, sf = 0, sc = 0, se = 0, see = 0, sg = 0;
    vec3 sgw(0.0f), sgf(0.0f), sn(0.0f);
    // The previous fit's normal; none (no correction) before the first or where ∇f vanished.
    const float g2 = length2(fit.gradient);
    const vec3 facing = k > 0 && g2 > 0 ? fit.gradient / sqrt(g2) : vec3(0.0f);
    samples.for_each_sample([&](vec3 p, int i) {
      const vec3 d = x - p;
      const vec3 n = samples.grid->normals[i];
      const float q = samples.grid->inv_h2[i];
      const float fi = glm::dot(d, n);
      const float phi = samples.grid->mass_of(i) * gaussian_weight(length2(d), q);
      float alpha = 1;
      if (k > 0) {
        const float residual = fi - fit.f;
        alpha = exp_nonpositive(-residual * residual * q * inv_sr2 - length2(n - fit.gradient) * inv_sn2);
      }
      const float w = alpha * phi;
      const vec3 gw = (-2 * q * w) * d;
      sw += w;
      sf += w * fi;
      sgw += gw;
      sgf += gw * fi;
      if constexpr (reported == ReportedNormal::filtered) {
        // The sample's plane, for c's noise: corrected for the curvature (as sc's term), so
        // that on a clean sphere every sample's is the same.
        const float e = k > 0 ? 0.5f * glm::dot(d, n + facing) : fi;
        const float g2w = length2(gw);
        sg += g2w;
        se += g2w * e;
        see += g2w * e * e;
      }
      sn += w * n;
      if (k > 0) {
        const float agree = glm::clamp((glm::dot(n, facing) - kRimlsCreaseBelow) / (kRimlsCurvedFrom - kRimlsCreaseBelow),
                                       0.0f, 1.0f);
        sc += w * agree * agree * (3 - 2 * agree) * glm::dot(d, facing - n);
      }
    });
    if (!(sw > 0)) return fit;  // every sample refused (or none): keep the last fit
    const float f = sf / sw;
    const vec3 gradient = (sgf - f * sgw + sn) / sw;
    const float change = length2(gradient - fit.gradient);
    fit.f = f;
    fit.gradient = gradient;
    if constexpr (reported == ReportedNormal::filtered) {
      const vec3 c = gradient - sn / sw;  // ∇f − m
      const float c2 = length2(c);
      const float v = sg > 0 ? (see - se * se / sg) / (sw * sw) : 0.0f;
      normal = c2 > 0 ? gradient - glm::clamp(v / c2, 0.0f, 1.0f) * c : gradient;
    }
    fit.valid = true;
    if (k > 0 && change < 1e-3f) {  // converged: n is the previous fit's to within 2°
      fit.correction = 0.5f * sc / sw;
      break;
    }
  }
  return fit;
}

// RIMLS's projection (project_by_fits): x → x − f(x)·∇f/‖∇f‖. The frame sits at the new
// point with the normal ∇f/‖∇f‖ (oriented as the samples' normals); the polynomial is its
// tangent plane, so that the ray tracer's next step is Newton's on f along the ray.
template <class Samples>
PSS_HOST_DEVICE Projection project_rimls(const Samples& samples, vec3 r, const ProjectionParams& params,
                                         vec3 normal_hint, int steps) {
  return project_by_fits(samples, r, params, normal_hint, steps, [&](vec3& x, float, Projection& out) {
    vec3 unfiltered;
    const RobustImplicit fit = fit_robust_implicit<ReportedNormal::gradient>(samples, x, unfiltered);
    const float g = glm::length(fit.gradient);
    if (!fit.valid || !(g > 0)) return -1.0f;
    out.normal = fit.gradient / g;
    const float f = fit.f + fit.correction;
    x -= f * out.normal;
    out.frame = Frame::from_normal(x, out.normal);
    out.polynomial = Polynomial{};
    return abs(f);
  });
}

// The normal `pss project` and `pss mesh` report at a RIMLS point x: the filtered one, from a
// fit at x (fit_robust_implicit). The ray tracer keeps ∇f: the filter's four more live values
// spilled its GPU kernels past their stack budget (1,048 bytes of 1,024 on sm_90), and its
// hits gained little (the noisy sphere of RenderTruth: 4.77° → 4.70°). `fallback` where the
// fit fails; oriented as it.
template <class Samples>
PSS_HOST_DEVICE vec3 filtered_rimls_normal(const Samples& samples, vec3 x, vec3 fallback) {
  vec3 filtered(0.0f);
  const RobustImplicit fit = fit_robust_implicit<ReportedNormal::filtered>(samples, x, filtered);
  const float m = glm::length(filtered);
  if (!fit.valid || !(m > 0)) return fallback;
  return glm::dot(filtered, fallback) < 0 ? -filtered / m : filtered / m;
}

}  // namespace pss
