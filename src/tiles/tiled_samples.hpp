// The samples of a cloud on disk made ready tile by tile (issue 28) for the steps that read
// each tile with its halo, as in core: their widths, which are kept (the outliers' passes),
// the whole cloud's layout of their grid, and their oriented normals where the step fits
// them (APSS, RIMLS; a mesh, whose sides they say). `pss project` (tiles/project.hpp) and
// `pss mesh` (tiles/mesh.hpp) start from these.
#pragma once

#include <cstddef>
#include <filesystem>
#include <span>
#include <vector>

#include "pss/backend/backend.hpp"
#include "pss/core/stats.hpp"
#include "pss/io/tiled_cloud.hpp"
#include "pss/points/outliers.hpp"
#include "pss/points/project_cloud.hpp"
#include "pss/points/sample_normals.hpp"
#include "pss/points/projection.hpp"
#include "pss/points/support.hpp"
#include "pss/points/unit_frame.hpp"
#include "pss/spatial/support_layout.hpp"
#include "pss/tiles/farm.hpp"
#include "orient_in_tiles.hpp"
#include "tile_works.hpp"

namespace pss {

// A tile and its halo in the unit frame, with each point's width and whether it is a sample.
struct UnitSet {
  TilePoints points;
  std::vector<vec3> unit;
  std::vector<float> h;
  std::vector<int> samples;  // indices into the set of the samples kept
  std::vector<vec3> sample_at;  // where samples were merged: UnitTile's
  std::vector<int> into;
  std::vector<vec3> normals;  // the samples' oriented ones, for APSS and RIMLS: UnitTile's
  const SupportLayout* layout = nullptr;  // UnitTile's
};

// What the projections' and the samples' normals' steps load of each tile.
struct UnitSets {
  const TiledCloud& cloud;
  const UnitFrame& frame;
  const std::vector<float>& h;
  const std::vector<char>& kept;
  std::span<const char> merge;
  double reach;  // unit: the widest ρ_i
  double halo;   // unit: merge_halo's
  const SupportLayout& layout;  // of the samples kept
  UnitSet load(int tile) const;  // with the halo `halo`
};

// The places the grid is built of: where samples merged, each cube's first point at its mean.
const std::vector<vec3>& grid_places(const UnitSet& s);

UnitTile unit_tile(const UnitSet& set);

// The oriented normals of the set's samples (UnitSet::normals), from the tiles that hold
// them: the tile's and those within the halo it was loaded with. Every sample within reach of
// the tile has one (its cube whole in the set: merge_halo); a merged sample beyond it may be
// a cube's part, whose first point in the set is no sample of the cloud: it reaches no point
// of the tile, and its normal is left zero.
std::vector<vec3> normals_of_set(const OrientedInTiles& samples, const UnitSets& sets, int tile, const UnitSet& set);

// The seams' turn of the samples' oriented normals over the tiles, as in core
// (points/seam_turn.hpp): sets samples.seam; how many normals it turned.
std::size_t turn_seams_in_tiles(const UnitSets& sets, OrientedInTiles& samples, TileFarm& farm);

// The file's normals of the samples over the tiles, as in core (points/sample_normals.hpp:
// file_normals), their seams turned; `normals` empty where they are left out.
struct FileNormalsInTiles {
  OrientedInTiles normals;  // by tile, one piece that does not turn
  std::size_t off_the_points = 0;       // where they were left out for that: how many samples' were off
  std::size_t turned = 0;
};
FileNormalsInTiles file_normals_in_tiles(const UnitSets& sets, float kappa, std::size_t window_points,
                                         const std::filesystem::path& folder, std::size_t buffer_bytes,
                                         TileFarm& farm);

struct TiledSamples {
  UnitFrame frame;
  ProjectionParams unit_params;  // the projection's, in the unit frame
  float kappa = 2;               // ρ_i / h_i
  std::vector<float> h;          // each point's width (unit)
  std::vector<char> merge;       // empty, or whether each point merges (points/merged_samples.hpp)
  std::vector<char> kept;        // whether each point is kept as a sample
  SupportLayout layout;          // of the samples kept
  double reach = 0;              // unit: the widest ρ_i
  double halo = 0;               // unit: a halo that holds every sample within reach, merged ones whole
  SupportWidths widths;          // least, median, largest (h is above)
  OutlierReport outliers;
  OrientedInTiles normals;       // the samples' oriented normals, by tile, where asked for or in the file
  NormalsUsed normals_used = NormalsUsed::none;  // whose those are
  std::size_t normals_turned = 0;                // the file's, contradicting the points
  std::size_t file_normals_off = 0;              // where the file's were left out for not following the points
  std::uint64_t without_direction = 0;           // points whose file normal has none
  bool file_hints() const { return normals_used == NormalsUsed::file; }
  UnitSets sets(const TiledCloud& cloud) const {
    return {cloud, frame, h, kept, merge, reach, halo, layout};
  }
};

// The steps above over `cloud`'s tiles for `params` (in the data's units), the samples'
// normals where the file has them (and params.normals takes them) or `with_normals` (then
// estimated where the file's are left out). Throws Error as project_cloud does.
TiledSamples tiled_samples(const TiledCloud& cloud, const ProjectionParams& params, bool with_normals,
                           Backend backend, std::size_t window_points, const std::filesystem::path& folder,
                           std::size_t buffer_bytes, Stats& stats, TileFarm& farm);

}  // namespace pss
