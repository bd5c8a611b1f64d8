#include "pss/points/surface_stats.hpp"

namespace pss {

void record_cloud_surface(Stats& stats, const ProjectionParams& params, const SupportWidths& widths,
                          NormalsUsed normals, std::size_t normals_turned, std::size_t file_normals_off,
                          std::int64_t outliers_set_aside) {
  auto& v = stats.values();
  v["params"] = {{"h", params.h},
                 {"rho", params.rho},
                 {"support", support_name(params.support)},
                 {"surface", surface_name(params.surface)},
                 {"normals", normals_used_name(normals)},
                 {"outliers", params.outliers == OutlierPolicy::keep ? "keep" : "set-aside"},
                 {"h_least", widths.least},
                 {"h_largest", widths.largest},
                 {"max_mls_iterations", params.max_mls_iterations}};
  v["outliers_set_aside"] = outliers_set_aside;
  v["points_merged"] = widths.merged_count;
  v["normals_turned"] = normals_turned;
  v["file_normals_off"] = file_normals_off;
}

void record_status_counts(Stats& stats, const StatusCounts& c) {
  stats.values()["status"] = {{"converged", c.converged},
                              {"not_converged", c.not_converged},
                              {"too_few_neighbours", c.too_few_neighbours},
                              {"degenerate_normal", c.degenerate_normal}};
}

}  // namespace pss
