// What --stats (and the Python module's full_output) records of a cloud's surface, for
// project and mesh alike: its parameters, and what was done to the samples and the file's
// normals (issue 26).
#pragma once

#include <cstddef>
#include <cstdint>

#include "pss/core/stats.hpp"
#include "pss/points/project_cloud.hpp"
#include "pss/points/sample_normals.hpp"

namespace pss {

// "params" (h, rho, support, surface, the normals used, outliers, the widths' least and
// largest, the MLS iterations), to which a command adds its own, and "outliers_set_aside",
// "points_merged", "normals_turned", "file_normals_off".
void record_cloud_surface(Stats& stats, const ProjectionParams& params, const SupportWidths& widths,
                          NormalsUsed normals, std::size_t normals_turned, std::size_t file_normals_off,
                          std::int64_t outliers_set_aside);

// "status": how many projections converged, did not, and why not.
void record_status_counts(Stats& stats, const StatusCounts& counts);

}  // namespace pss
