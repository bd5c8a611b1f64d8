#include "pss/points/project_cloud.hpp"

#include <cmath>
#include <string>

#include "pss/backend/cpu/parallel_for.hpp"
#include "pss/core/error.hpp"
#include "pss/points/orient_normals.hpp"

namespace pss {

void validate(const ProjectionParams& p) {
  auto positive = [](float v) { return v > 0 && std::isfinite(v); };
  if (!positive(p.h)) throw Error("h must be a positive number (got " + std::to_string(p.h) + ")");
  if (!positive(p.rho)) throw Error("rho must be a positive number (got " + std::to_string(p.rho) + ")");
  if (p.max_mls_iterations < 1) throw Error("MLS iterations must be at least 1");
}

CloudProjection project_cloud(const PointCloud& input, const ProjectionParams& params, Backend backend,
                              Stats& stats) {
  validate(params);
  const std::size_t n = input.size();
  std::vector<ProjectedPoint> projected(n);
  {
    ScopedPhase phase(stats, "spatial index");
    const UniformGrid grid(input.positions, params.rho);
    phase.stop();
    // Without input normals the eigenvector's sign is arbitrary; orientation comes after.
    const std::vector<vec3> hints = input.has_normals() ? input.normals : std::vector<vec3>(n, vec3(0.0f));
    ScopedPhase projection(stats, "projection");
    Progress progress("projecting", std::int64_t(n));
    const GridView view = grid.view();
    if (backend == Backend::cuda) {
      cuda::project_points(view, input.positions, hints, params, projected, &progress);
    } else {
      cpu::parallel_for(std::int64_t(n), [&](std::int64_t i) {
        projected[i] = project_point(view, input.positions[i], hints[i], params);
      }, &progress);
    }
  }

  CloudProjection out;
  out.cloud.positions.resize(n);
  out.cloud.normals.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    out.cloud.positions[i] = projected[i].point;
    out.cloud.normals[i] = projected[i].normal;
    switch (projected[i].status) {
      case ProjectionStatus::converged: ++out.counts.converged; break;
      case ProjectionStatus::not_converged: ++out.counts.not_converged; break;
      case ProjectionStatus::too_few_neighbours: ++out.counts.too_few_neighbours; break;
      case ProjectionStatus::degenerate_normal: ++out.counts.degenerate_normal; break;
    }
  }
  if (!input.has_normals()) {
    ScopedPhase phase(stats, "orient normals");
    orient_normals_consistently(out.cloud.positions, out.cloud.normals, params.h);
  }
  return out;
}

}  // namespace pss
