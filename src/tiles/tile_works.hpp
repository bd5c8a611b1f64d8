// The steps of `pss project` tile by tile that any process may work on (tiles/farm.hpp): each
// a request's bytes in, a result's bytes out, a pure function of the request, so that rank 0
// and the others give the same result for the same tile.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "pss/backend/backend.hpp"
#include "pss/io/tiled_cloud.hpp"
#include "pss/mesh/mesh_cloud_piece.hpp"
#include "pss/points/orient_normals.hpp"
#include "pss/points/project_points.hpp"
#include "pss/points/seam_turn.hpp"
#include "pss/points/support_steps.hpp"
#include "pss/points/visibility.hpp"
#include "pss/spatial/support_layout.hpp"

namespace pss {

// A tile's notes (tiles/farm.hpp) that name its own points: their indices in the cloud.
std::vector<std::byte> own_points_notes(const TilePoints& points);
std::vector<std::uint64_t> own_points(std::span<const std::byte> notes);

// A tile and its halo in the unit frame: the tile's own points first.
struct UnitTile {
  std::span<const vec3> unit;
  std::span<const float> h;      // each point's width
  std::span<const int> samples;  // the points kept as samples
  std::size_t own = 0;
  // Where samples were merged (points/merged_samples.hpp), both as long as `unit`, else
  // empty: the positions the grid is built of (each cube's first point at its cube's mean),
  // and each point's cube's first point (SupportGrid::set_members: the samples' masses).
  std::span<const vec3> sample_at;
  std::span<const int> into;
  // The samples' oriented normals that APSS and RIMLS fit (points/sample_normals.hpp), as
  // long as `unit` (a point that is no sample: any), or empty for MLS.
  std::span<const vec3> normals;
  // The whole cloud's cells (spatial/support_layout.hpp), which the tile's grid takes a part
  // of, so that its sums run as in core; `samples` ascending in the cloud's order.
  const SupportLayout* layout = nullptr;
};

// The outliers' distance (points/outliers.hpp) of each own sample of the tile.
std::vector<std::byte> outliers_request(const UnitTile& tile);
std::vector<std::byte> work_outliers(std::span<const std::byte> request);
struct TileOutliers {
  std::vector<float> distance;  // each own point's, NaN where it is no sample
  std::vector<float> mass;      // each own sample's (SupportGridView::mass_of), NaN where no sample
  std::vector<float> held;      // each own sample's neighbours' masses (OutlierDistanceKernel), likewise
};
TileOutliers outliers_result(std::span<const std::byte> result);

// The projection of each own point (at `unit`) of the tile onto the surface of its samples;
// where the file's normals orient it (`file_normals`: each point's in the set, the samples'
// turned ones in `tile.normals`), with their hints, as in core.
std::vector<std::byte> projection_request(const UnitTile& tile, const ProjectionParams& unit_params, Backend backend,
                                          std::span<const vec3> file_normals = {});
std::vector<std::byte> work_projection(std::span<const std::byte> request);
struct TileProjections {
  std::vector<int> order;  // the own points in the grid's order, as they were projected
  std::vector<ProjectedPoint> projected;  // in that order
};
TileProjections projection_result(std::span<const std::byte> result);

// The unoriented normal of each own sample of the tile, as in core (points/sample_normals.hpp):
// its WLS plane's at the sample's place.
std::vector<std::byte> sample_normals_request(const UnitTile& tile, const ProjectionParams& unit_params,
                                              Backend backend);
std::vector<std::byte> work_sample_normals(std::span<const std::byte> request);
struct TileSampleNormals {
  std::vector<int> sample;  // each own sample's place in the set
  std::vector<vec3> normal;
  std::vector<ProjectionStatus> status;  // whether its plane was fitted
};
TileSampleNormals sample_normals_result(std::span<const std::byte> result);

// The file's normal of each own sample of the tile, as in core (points/sample_normals.hpp:
// file_normal_of, off_its_neighbours), from `file_normals` and `cloud_index`, each point's in
// the set.
std::vector<std::byte> file_normals_request(const UnitTile& tile, std::span<const vec3> file_normals,
                                            std::span<const std::uint64_t> cloud_index);
std::vector<std::byte> work_file_normals(std::span<const std::byte> request);
struct TileFileNormals {
  std::vector<int> sample;   // each own sample's place in the set
  std::vector<vec3> normal;  // unit length, or zero where it has no direction
  std::vector<char> off;     // more than 45° off its neighbours' plane
};
TileFileNormals file_normals_result(std::span<const std::byte> result);

// The orientation of a tile's projected points and its halo's (points/orient_normals.hpp:
// orient_normals_in_parts), in the unit frame. Where samples were merged, `sample` holds, for
// each point, the place in the set of the point its merged sample stands at, or −1 where it
// stands for itself: the tree grows over those, and each other point takes its sample's side
// and part, as in core (project_cloud.cpp); or kSampleNotInSet where the set lacks its sample's
// point (in the halo): a node of the tile's tree then, but it casts no rays, as in core it is
// no node. Empty: every point stands for itself.
inline constexpr int kSampleNotInSet = -2;
// The set's rays go through `occupancy`, the whole cloud's samples' (points/visibility.hpp).
std::vector<std::byte> orientation_request(std::span<const vec3> points, std::span<const vec3> normals,
                                           std::span<const float> radius, std::span<const std::uint64_t> id,
                                           const Occupancy& occupancy, std::span<const int> sample = {});
std::vector<std::byte> work_orientation(std::span<const std::byte> request);
struct TileOrientation {
  std::vector<vec3> normals;  // oriented by the tree
  OrientedParts parts;
  std::vector<char> seen_turned;        // per point, whether the rays' signs turn it (tiles/orient.hpp)
  std::vector<std::int8_t> seen_votes;  // per point, its rays' vote with those signs; 0 where none
};
TileOrientation orientation_result(std::span<const std::byte> result, std::size_t points);

// A tile and its halo for the adaptive widths (points/support_steps.hpp): each point's index
// in the cloud and margin (none: the set is the whole cloud).
struct MarginTile {
  std::span<const vec3> unit;
  std::span<const std::uint64_t> id;
  std::span<const float> margin;
  std::size_t own = 0;
  std::uint64_t cloud_size = 0;
  double scale = 1;
};

// The widths' first pass (tiles/support.hpp): each own sample's spacing and its least
// neighbour's, whether it looks like a row's, and σ at the noise queries among them (every
// `stride`-th index); nothing where the halo did not hold every answer.
std::vector<std::byte> spacing_request(const MarginTile& tile, std::uint64_t stride);
std::vector<std::byte> work_spacing(std::span<const std::byte> request);
struct TileSpacing {
  bool complete = false;
  std::vector<float> spacing, least;  // of each own sample
  std::uint64_t row_like = 0;
  std::vector<std::uint64_t> query;  // each noise query's index over the stride
  std::vector<vec3> at;
  std::vector<float> measured;
};
TileSpacing spacing_result(std::span<const std::byte> result, std::size_t own);

// The second pass: each own sample's width, from the first pass's spacings of the tile and
// its halo, their median over the cloud, and σ at every noise query of the cloud.
struct WidthsInputs {
  std::span<const float> spacing, least;  // of each point of the tile and its halo
  float median_spacing = 0, h = 0, widest = 0, kappa = 2;
  std::span<const vec3> noise_at;
  std::span<const float> noise_measured;
};
std::vector<std::byte> widths_request(const MarginTile& tile, const WidthsInputs& inputs);
std::vector<std::byte> work_widths(std::span<const std::byte> request);
struct TileWidths {
  bool complete = false;
  std::vector<float> h;       // of each own sample
  std::vector<char> merged;  // likewise (support.hpp, merges_samples)
};
TileWidths widths_result(std::span<const std::byte> result, std::size_t own);

// The piece of a cloud's mesh in the cubes `kept` of `lattice` (mesh/mesh_cloud_piece.hpp),
// from the tile's samples, their oriented normals and its halo's, in the unit frame.
struct MeshPieceInputs {
  Lattice lattice;
  CubeBox kept;
  float crease_angle = 30;
  float asked_cell = 0;  // the cell each vertex takes, or 0: its nearest covering sample's share
  float least_cell = 0;
};
std::vector<std::byte> mesh_request(const UnitTile& tile, const ProjectionParams& unit_params,
                                    const MeshPieceInputs& inputs, Backend backend);
std::vector<std::byte> work_mesh(std::span<const std::byte> request);
CloudMeshPiece mesh_result(std::span<const std::byte> result);

// The seams' turn of the samples' oriented normals (points/seam_turn.hpp) over a tile's own
// samples, with its halo's (their normals in the tile): which samples join a patch, the
// evidence between the patches (`patch`: each point's patch, kNoPatch where it is no
// sample), or, after the groups' turn, the stragglers' says (`settled`: each point's patch
// holds kFewestPerPatch samples or more).
enum class SeamStep : std::uint8_t { joins = 0, evidence = 1, stragglers = 2 };
std::vector<std::byte> seam_turn_request(const UnitTile& tile, SeamStep step, std::span<const std::uint32_t> patch = {},
                                         std::span<const char> settled = {});
std::vector<std::byte> work_seam_turn(std::span<const std::byte> request);
struct TileSeamTurn {
  std::vector<int> joined, root;  // joins: each point of the set in a patch of the tile's joins, and its least point
  PatchEvidence evidence;
  std::vector<int> straggler;  // stragglers: each own straggling sample, and its say
  std::vector<double> say;
};
TileSeamTurn seam_turn_result(std::span<const std::byte> result, SeamStep step);

}  // namespace pss
