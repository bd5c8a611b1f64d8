// The samples' oriented unit normals that APSS and RIMLS fit (issue 26): the file's when it
// has them, else estimated from the points (each sample's WLS plane, paper Eq. 1, at
// itself), oriented consistently (orient_normals.hpp) and their seams turned
// (turn_flipped_normals.hpp: where the tree crossed a fold).
#pragma once

#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#include "pss/backend/backend.hpp"
#include "pss/core/stats.hpp"
#include "pss/points/project_points.hpp"
#include "pss/points/projection.hpp"
#include "pss/spatial/support_grid.hpp"

namespace pss {

// Why the normals are what they are, for the summary line and --stats.
enum class NormalsUsed : unsigned char { none, file, estimated };

// The file's normals of the grid's samples, in its sorted order, unit length, those that
// contradict the points turned (turn_flipped_normals.hpp); empty when params.normals is
// NormalSource::estimate, the cloud has none (`input_normals` empty; in its input order), one
// has no direction (zero, not finite): a file that lies about some cannot be trusted for any,
// or over a third lie more than 45° off their neighbours' plane (random normals, or one
// direction for all): they do not follow the points.
struct FileNormals {
  std::vector<vec3> sorted;
  std::size_t turned = 0;
  std::size_t off_the_points = 0;  // where they were left out for that: how many samples' were off
};
FileNormals file_normals(const SupportGrid& grid, std::span<const vec3> input_normals, const ProjectionParams& params,
                         Stats& stats);

// The steps of file_normals, for tiles (src/tiles/file_normals_in_tiles.cpp) as for core:
// sorted sample k's file normal, unit length (a merged sample's the mean of its points',
// each turned to the sample's own side, summed in the cloud's order: `cloud_index` of each
// input point, or empty where the input is in it), or zero where it has no direction;
vec3 file_normal_of(const SupportGrid& grid, std::span<const vec3> input_normals, std::size_t k,
                    std::span<const std::uint64_t> cloud_index);
// whether it lies more than 45° off the plane of its neighbours (the outliers' plane:
// points/outliers.hpp), where they fit one;
bool off_its_neighbours(const SupportGridView& view, int k, vec3 normal);
// whether `off` of `samples` so off leave the file's normals out.
bool too_many_off(std::size_t off, std::size_t samples);

// The file's normal of a point that is no sample of its own (set aside, or merged into one),
// a hint of which side its projection faces: its own, unit length, on the side of the nearest
// sample's whose support holds it (`sorted_normals`, the grid's samples' file normals); zero
// where it has no direction.
vec3 hint_beside(const SupportGridView& view, std::span<const vec3> sorted_normals, vec3 position, vec3 normal);

// The projection that estimates a sample's normal: its WLS plane's (Eq. 1) at the sample,
// wherever the sample lies (no border).
ProjectionParams sample_plane_params(const ProjectionParams& params);

// A sample's estimated normal from its plane's fit: none (zero) where no plane was fitted (too
// few neighbours, or all on a line), which APSS and RIMLS then cannot fit: a cloud on a line
// projects nowhere under them, as under MLS, and says so.
inline vec3 fitted_normal(const ProjectedPoint& plane) {
  const bool fitted = plane.status == ProjectionStatus::converged || plane.status == ProjectionStatus::not_converged;
  return fitted ? plane.normal : vec3(0.0f);
}

// One normal per sample of `grid`, in its sorted order: the file's when it has them, else
// estimated on `backend` (phase "sample normals") and oriented.
std::vector<vec3> sample_normals(const SupportGrid& grid, const FileNormals& file, const ProjectionParams& params,
                                 Backend backend, Stats& stats, NormalsUsed& used);

// Whether `params` needs the samples' normals (APSS, RIMLS), and gives the grid them.
void prepare_sample_normals(SupportGrid& grid, const FileNormals& file, const ProjectionParams& params, Backend backend,
                            Stats& stats, NormalsUsed& used);

const char* normals_used_name(NormalsUsed used);

}  // namespace pss
