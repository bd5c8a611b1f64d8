// The file's normals of the samples tile by tile, as in core (points/sample_normals.hpp:
// file_normals): each tile gives its own samples' (a merged sample's the mean of its cube's,
// the cube whole in its halo) and whether each lies more than 45° off its neighbours' plane;
// then, where every sample's has a direction and at most a third are off, the seams' turn
// over the tiles mends what contradicts the points (turn_seams_in_tiles).
#include "pss/core/error.hpp"
#include "pss/core/progress.hpp"
#include "pss/points/sample_normals.hpp"
#include "tile_bytes.hpp"
#include "tiled_samples.hpp"

namespace pss {

FileNormalsInTiles file_normals_in_tiles(const UnitSets& sets, const std::filesystem::path& folder,
                                         std::size_t buffer_bytes, TileFarm& farm) {
  const TiledCloud& cloud = sets.cloud;
  FileNormalsInTiles out;
  auto by_tile = std::make_unique<BucketFile>(folder, cloud.tiles(), sizeof(Oriented), buffer_bytes);
  std::size_t samples = 0, off = 0;
  bool directed = true;
  {
    Progress progress("file normals", std::int64_t(cloud.size()));
    farm.run(
        TileStep::file_normals, cloud.tiles_with_points(),
        [&](int t) {
          const UnitSet set = sets.load(t);
          ByteWriter notes;  // the own points' indices and places as samples
          notes.put_array(std::span(set.points.index).first(set.points.own));
          notes.put_array(std::span<const vec3>(grid_places(set)).first(set.points.own));
          return TileRequest{file_normals_request(unit_tile(set), set.points.normals, set.points.index), notes.take()};
        },
        [&](int t, std::span<const std::byte> result, std::span<const std::byte> notes, int) {
          const TileFileNormals done = file_normals_result(result);
          ByteReader read(notes);
          const std::vector<std::uint64_t> index = read.get_array<std::uint64_t>();
          const std::vector<vec3> at = read.get_array<vec3>();
          if (at.size() != index.size()) throw Error("a tile's file normals do not hold together");
          for (std::size_t k = 0; k < done.sample.size(); ++k) {
            const auto i = std::size_t(done.sample[k]);
            if (i >= index.size()) throw Error("a tile's file normals do not hold together");
            directed = directed && has_direction(done.normal[k]);
            off += done.off[k] != 0;
            ++samples;
            const Oriented r{index[i], at[i], done.normal[k], 0, ProjectionStatus::converged, true};
            by_tile->append(t, &r);
          }
          progress.advance(std::int64_t(index.size()));
        });
  }
  by_tile->flush();
  // As in core: a file that gives some sample no direction cannot be trusted for any, nor one
  // whose normals do not follow the points.
  if (!directed) return out;
  if (too_many_off(off, samples)) {
    out.off_the_points = off;
    return out;
  }
  out.normals.by_tile = std::move(by_tile);
  out.normals.flip = {0};
  out.turned = turn_seams_in_tiles(sets, out.normals, farm);
  return out;
}

}  // namespace pss
