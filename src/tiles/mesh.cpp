#include "pss/tiles/mesh.hpp"

#include <algorithm>
#include <cmath>

#include "pss/backend/cpu/parallel_for.hpp"
#include "pss/core/error.hpp"
#include "pss/core/progress.hpp"
#include "pss/mesh/coarsen.hpp"
#include "pss/mesh/weld.hpp"
#include "tile_records.hpp"
#include "tiled_samples.hpp"

namespace pss {

namespace {

// The cubes whose centres lie in each tile (TiledCloud::tile_cell_of): along each axis, the
// cubes' columns of tiles, never falling, so that each tile's cubes are a box.
class CubeOwners {
 public:
  CubeOwners(const TiledCloud& cloud, const UnitFrame& frame, const Lattice& lattice) {
    for (int a = 0; a < 3; ++a) {
      column_[a].resize(std::size_t(std::max(lattice.size[a] - 1, 0)));
      for (std::size_t i = 0; i < column_[a].size(); ++i) {
        vec3 unit = lattice.position(ivec3(0));
        unit[a] = float(lattice.origin[a] + (double(i) + 0.5) * lattice.cell);
        column_[a][i] = cloud.tile_cell_of(frame.from_unit(unit))[a];
      }
    }
  }
  CubeBox of(ivec3 tile_cell) const {
    CubeBox box;
    for (int a = 0; a < 3; ++a) {
      const auto& c = column_[a];
      box.lo[a] = int(std::lower_bound(c.begin(), c.end(), tile_cell[a]) - c.begin());
      box.hi[a] = int(std::upper_bound(c.begin(), c.end(), tile_cell[a]) - c.begin());
    }
    return box;
  }

 private:
  std::vector<int> column_[3];
};

bool empty(const CubeBox& box) { return box.lo.x >= box.hi.x || box.lo.y >= box.hi.y || box.lo.z >= box.hi.z; }

// The tiles with points, and those within `reach` of them: a surface near a tile's edge
// may cross into a tile of no points of its own.
std::vector<int> tiles_to_mesh(const TiledCloud& cloud, double reach) {
  std::vector<int> tiles = cloud.tiles_with_points();
  const std::size_t with_points = tiles.size();
  for (std::size_t k = 0; k < with_points; ++k)
    for (const int t : cloud.tiles_near(tiles[k], float(reach))) tiles.push_back(t);
  std::sort(tiles.begin(), tiles.end());
  tiles.erase(std::unique(tiles.begin(), tiles.end()), tiles.end());
  return tiles;
}

// The parts of the mesh held by fewer than kMinPartSamples samples (remove_unsupported_parts),
// counted over each tile's own samples, as the in-core grid holds them.
CountSamples count_in_tiles(const TiledCloud& cloud, const TiledSamples& samples) {
  return [&cloud, &samples](std::span<const vec3> centre, std::span<const float> radius, std::span<int> inside) {
    const UnitSets sets = samples.sets(cloud);
    for (const int t : cloud.tiles_with_points()) {
      const Aabb world = cloud.tile_box(t);
      const vec3 lo = samples.frame.to_unit(world.lo), hi = samples.frame.to_unit(world.hi);
      std::vector<int> near;  // the parts not held yet whose spheres reach the tile
      for (std::size_t p = 0; p < centre.size(); ++p) {
        if (inside[p] >= kMinPartSamples) continue;
        const vec3 d = glm::max(glm::max(lo - centre[p], centre[p] - hi), vec3(0.0f));
        if (glm::length(d) <= radius[p] * (1 + 1e-5f) + 1e-6f) near.push_back(int(p));
      }
      if (near.empty()) continue;
      const UnitSet set = sets.load(t);
      const std::vector<vec3>& at = grid_places(set);
      cpu::parallel_for(std::int64_t(near.size()), [&](std::int64_t k) {
        const auto p = std::size_t(near[std::size_t(k)]);
        for (const int i : set.samples)
          if (std::size_t(i) < set.points.own && glm::length(at[std::size_t(i)] - centre[p]) <= radius[p]) ++inside[p];
      });
    }
  };
}

}  // namespace

TiledCloudMesh mesh_in_tiles(const TiledCloud& cloud, const MeshParams& params, Backend backend,
                             const std::filesystem::path& folder, std::size_t window_points,
                             std::size_t buffer_bytes, Stats& stats, TileFarm& farm) {
  const ProjectionParams& projection = params.projection;
  TiledCloudMesh result;
  CloudMesh& out = result.mesh;
  out.cell = mesh_cell(params);
  if (cloud.size() < 3)
    throw Error("a mesh needs at least 3 points (the cloud has " + std::to_string(cloud.size()) + ")");
  // Every operator's mesh needs the samples' oriented normals, the file's or estimated: they
  // say which side is out.
  TiledSamples samples =
      tiled_samples(cloud, projection, true, backend, window_points, folder, buffer_bytes, stats, farm);
  out.widths = samples.widths;
  out.outliers = samples.outliers;
  out.normals = samples.normals_used;
  out.normals_turned = samples.normals_turned;
  out.file_normals_off = samples.file_normals_off;
  result.normals_without_direction = samples.without_direction;
  const UnitFrame& frame = samples.frame;
  const double cell = double(out.cell) / frame.scale;  // unit
  const float asked = params.cell > 0 ? float(double(params.cell) / frame.scale) : 0.0f;

  // The lattice as mesh_cloud's (in the unit frame): past the samples as far as the surface may reach.
  const Lattice lattice =
      cloud_lattice(cloud.bounds(), frame, projection.borders, samples.reach, cell, params.cell > 0);
  check_band(expected_band_cubes(samples.h, cell), double(out.cell), "cloud");
  const CubeOwners owners(cloud, frame, lattice);

  // Each tile's set holds the samples that any corner of its march reads: those within reach
  // of the corners kPieceMargin cubes past its box, whose projections move up to a support.
  UnitSets wide = samples.sets(cloud);
  wide.halo = samples.halo + samples.reach + (kPieceMargin + 2) * std::sqrt(3.0) * cell;
  std::vector<int> tiles = tiles_to_mesh(cloud, world_halo(wide.halo, frame));
  std::erase_if(tiles, [&](int t) { return empty(owners.of(cloud.tile_cell(t))); });
  MeshWelder welder;
  result.points_per_rank.assign(std::size_t(farm.ranks()), 0);
  {
    ScopedPhase phase(stats, "mesh", false);  // its Progress shows it
    Progress progress("meshing tiles", std::int64_t(tiles.size()));
    farm.run(
        TileStep::mesh, tiles,
        [&](int t) {
          UnitSet set = wide.load(t);
          set.normals = normals_of_set(samples.normals, wide, t, set);
          const MeshPieceInputs inputs{lattice, owners.of(cloud.tile_cell(t)), params.crease_angle, asked,
                                       float(cell)};
          return TileRequest{mesh_request(unit_tile(set), samples.unit_params, inputs, backend), {}};
        },
        [&](int t, std::span<const std::byte> bytes, std::span<const std::byte>, int rank) {
          const CloudMeshPiece piece = mesh_result(bytes);
          welder.add(piece.piece, piece.cell);
          out.counts.corners += piece.counts.corners;
          out.counts.cubes_visited += piece.counts.cubes_visited;
          out.counts.cubes_crossed += piece.counts.cubes_crossed;
          out.counts.cubes_refused += piece.counts.cubes_refused;
          out.counts.crease_flips += piece.counts.crease_flips;
          result.points_per_rank[std::size_t(rank)] += cloud.tile_size(t);
          progress.advance(1);
        });
  }
  std::vector<float> cells;
  {
    ScopedPhase phase(stats, "weld", true);
    out.mesh = welder.weld(cells, out.counts);
  }
  {
    ScopedPhase phase(stats, "coarsen", true);
    coarsen_mesh(out.mesh, cells, out.counts);
  }
  out.counts.unsupported_parts = remove_unsupported_parts(out.mesh, count_in_tiles(cloud, samples));
  for (vec3& p : out.mesh.positions) p = frame.from_unit(p);
  out.mesh.origin = cloud.origin();
  finish_cloud_mesh(out, projection);
  return result;
}

}  // namespace pss
