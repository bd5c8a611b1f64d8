// The projection onto the surface a cloud defines, whichever operator `--surface` chose
// (ProjectionParams::surface): what `pss project` and the ray tracer call.
#pragma once

#include <type_traits>

#include "pss/points/algebraic_sphere.hpp"
#include "pss/points/borders.hpp"
#include "pss/points/projection.hpp"
#include "pss/points/robust_implicit.hpp"

namespace pss {

// MLS is the paper's P(r) (projection.hpp). APSS and RIMLS fit at r once with
// PlaneFitMethod::wls (the ray tracer iterates itself, as the paper's §5.2 loop) and move
// their fit to the last point up to max_mls_iterations times with PlaneFitMethod::mls, as
// MLS moves its weights to q. Every operator reads N(r), gathered once here: Nb is MLS's
// storage of it (neighbourhood.hpp); APSS and RIMLS read the samples' indices. Where the
// two are one type (on the GPU) one gather serves all three, so that a kernel's stack holds
// one neighbourhood, not one per operator.
template <class Nb = Neighbourhood>
PSS_HOST_DEVICE Projection project_onto_surface(const SupportGridView& grid, vec3 r, const ProjectionParams& params,
                                                vec3 normal_hint, float bounded_within = kInfinity) {
  const int steps = params.plane == PlaneFitMethod::mls ? params.max_mls_iterations : 1;
  // With BorderMode::clip, whether P(r) lies among N(r) (points/borders.hpp), read from the
  // same gather; only where P(r) is within `bounded_within` of r (the ray tracer asks where
  // it would take the point as a hit).
  auto bounded = [&](const auto& samples, Projection p) {
    if (params.borders == BorderMode::clip && p.status != ProjectionStatus::too_few_neighbours &&
        length2(p.point - r) < bounded_within * bounded_within)
      p.surrounded = samples_surround(samples, p.point, p.normal);
    return p;
  };
  if constexpr (std::is_same_v<Nb, SampleIndices>) {
    const Nb samples(grid, r);
    switch (params.surface) {
      case SurfaceOperator::apss: return bounded(samples, project_apss(samples, r, params, normal_hint, steps));
      case SurfaceOperator::rimls: return bounded(samples, project_rimls(samples, r, params, normal_hint, steps));
      case SurfaceOperator::mls: break;
    }
    return bounded(samples, project_mls(samples, r, params, normal_hint));
  } else {
    if (params.surface == SurfaceOperator::mls) {
      const Nb neighbours(grid, r);
      return bounded(neighbours, project_mls(neighbours, r, params, normal_hint));
    }
    const SampleIndices samples(grid, r);
    return bounded(samples, params.surface == SurfaceOperator::apss
                                ? project_apss(samples, r, params, normal_hint, steps)
                                : project_rimls(samples, r, params, normal_hint, steps));
  }
}

// The normal `pss project` and `pss mesh` report at a projected point with the projection's
// normal n: RIMLS's filtered there (filtered_rimls_normal), oriented as n; the others' n.
PSS_HOST_DEVICE inline vec3 reported_normal(const SupportGridView& grid, vec3 point, vec3 n,
                                            const ProjectionParams& params) {
  if (params.surface != SurfaceOperator::rimls) return n;
  return filtered_rimls_normal(SampleIndices(grid, point), point, n);
}

}  // namespace pss
