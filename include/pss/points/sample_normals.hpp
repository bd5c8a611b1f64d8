// The samples' oriented unit normals that APSS and RIMLS fit (issue 26): the file's when it
// has them, else estimated from the points (each sample's WLS plane, paper Eq. 1, at
// itself) and oriented consistently (orient_normals.hpp).
#pragma once

#include <span>
#include <vector>

#include "pss/backend/backend.hpp"
#include "pss/core/stats.hpp"
#include "pss/points/projection.hpp"
#include "pss/spatial/support_grid.hpp"

namespace pss {

// Why the normals are what they are, for the summary line and --stats.
enum class NormalsUsed : unsigned char { none, file, estimated };

// One normal per sample of `grid`, in its sorted order. `file_normals` are the cloud's, in
// its input order (empty when it has none): taken, normalised, when params.normals is
// NormalSource::file and every one has a length; else estimated on `backend` (phase
// "sample normals") and oriented.
std::vector<vec3> sample_normals(const SupportGrid& grid, std::span<const vec3> file_normals,
                                 const ProjectionParams& params, Backend backend, Stats& stats, NormalsUsed& used);

// Whether `params` needs the samples' normals (APSS, RIMLS), and gives the grid them.
void prepare_sample_normals(SupportGrid& grid, std::span<const vec3> file_normals, const ProjectionParams& params,
                            Backend backend, Stats& stats, NormalsUsed& used);

const char* normals_used_name(NormalsUsed used);

}  // namespace pss
