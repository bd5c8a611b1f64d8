// The file's normals of the samples tile by tile, as in core (points/sample_normals.hpp:
// file_normals): each tile gives its own samples' (a merged sample's the mean of its cube's,
// the cube whole in its halo) and whether each lies more than 45° off its neighbours' plane;
// then, where every sample's has a direction and at most a third are off, the seams' turn
// over the tiles mends what contradicts the points (turn_seams_in_tiles), and the rays what
// the seams' turn missed (face_as_seen_in_tiles).
#include <algorithm>
#include <utility>

#include "pss/core/error.hpp"
#include "pss/core/progress.hpp"
#include "pss/points/orient_normals.hpp"
#include "pss/points/sample_normals.hpp"
#include "tile_bytes.hpp"
#include "tiled_samples.hpp"

namespace pss {

namespace {

// As in core (orient_normals.hpp: face_file_normals_as_seen): the file's normals, as the
// seams' turn left them, oriented over the tiles as estimated ones are, and in each part
// whose rays decide, where a share of the file's face against that but not nearly all, those
// turn (file.seam). `moved`: per tile, the farthest a sample's place lies from its point.
// Returns how many turned.
std::size_t face_as_seen_in_tiles(const UnitSets& sets, float kappa, std::span<const double> moved,
                                  std::size_t window_points, const std::filesystem::path& folder,
                                  std::size_t buffer_bytes, TileFarm& farm, OrientedInTiles& file) {
  const TiledCloud& cloud = sets.cloud;
  const auto as_left = [&](const Oriented& r) { return file.turned(r) ? -r.normal : r.normal; };
  OrientedInTiles along = [&] {
    BucketFile records(folder, cloud.tiles(), sizeof(Projected), buffer_bytes);
    for (int t = 0; t < cloud.tiles(); ++t)
      file.by_tile->for_each_record<Oriented>(t, [&](const Oriented& r) {
        const Projected p{r.index, r.index, r.point, as_left(r), kappa * sets.h[std::size_t(r.index)],
                          ProjectionStatus::converged};
        records.append(t, &p);
      });
    records.flush();
    const OrientationInputs in{cloud, sets.frame, records, moved, sets.reach, false};
    return orient_in_tiles(in, window_points, true, folder, buffer_bytes, farm, "orient file normals");
  }();
  along.ordered.reset();
  // Each sample's part, and whether the file's normal faces against the orientation there.
  const auto each_sample = [&](auto&& f) {
    for (int t = 0; t < cloud.tiles(); ++t) {
      std::vector<std::pair<std::uint64_t, vec3>> left;
      file.by_tile->for_each_record<Oriented>(t, [&](const Oriented& r) { left.push_back({r.index, as_left(r)}); });
      std::sort(left.begin(), left.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
      along.by_tile->for_each_record<Oriented>(t, [&](const Oriented& r) {
        const auto at = std::lower_bound(left.begin(), left.end(), r.index,
                                         [](const auto& a, std::uint64_t i) { return a.first < i; });
        if (at == left.end() || at->first != r.index) throw Error("the file's normals in tiles do not hold together");
        const vec3 oriented = along.turned(r) ? -r.normal : r.normal;
        f(r.index, along.pieces.part[r.piece], glm::dot(oriented, at->second) < 0);
      });
    }
  };
  const std::size_t pieces = along.pieces.part.size();
  std::vector<std::uint64_t> size(pieces, 0), against(pieces, 0);  // by part
  each_sample([&](std::uint64_t, std::uint32_t part, bool is_against) {
    size[part] += 1;
    against[part] += is_against;
  });
  std::vector<char> mends(pieces, 0);
  for (std::size_t p = 0; p < pieces; ++p) {
    const double share = double(against[p]) / double(std::max<std::uint64_t>(size[p], 1));
    mends[p] = along.pieces.seen[p] && share >= kFileAgainstShare && share <= 1 - kFileAgainstShare;
  }
  std::size_t turned = 0;
  each_sample([&](std::uint64_t index, std::uint32_t part, bool is_against) {
    if (!mends[part] || !is_against) return;
    if (file.seam.empty()) file.seam.assign(std::size_t(cloud.size()), 0);
    file.seam[std::size_t(index)] ^= 1;
    ++turned;
  });
  return turned;
}

}  // namespace

FileNormalsInTiles file_normals_in_tiles(const UnitSets& sets, float kappa, std::size_t window_points,
                                         const std::filesystem::path& folder, std::size_t buffer_bytes,
                                         TileFarm& farm) {
  const TiledCloud& cloud = sets.cloud;
  FileNormalsInTiles out;
  auto by_tile = std::make_unique<BucketFile>(folder, cloud.tiles(), sizeof(Oriented), buffer_bytes);
  std::size_t samples = 0, off = 0;
  std::vector<double> moved(std::size_t(cloud.tiles()), 0.0);  // a merged sample's place from its point
  bool directed = true;
  {
    Progress progress("file normals", std::int64_t(cloud.size()));
    farm.run(
        TileStep::file_normals, cloud.tiles_with_points(),
        [&](int t) {
          const UnitSet set = sets.load(t);
          ByteWriter notes;  // the own points' indices, unit positions and places as samples
          notes.put_array(std::span(set.points.index).first(set.points.own));
          notes.put_array(std::span<const vec3>(set.unit).first(set.points.own));
          notes.put_array(std::span<const vec3>(grid_places(set)).first(set.points.own));
          return TileRequest{file_normals_request(unit_tile(set), set.points.normals, set.points.index), notes.take()};
        },
        [&](int t, std::span<const std::byte> result, std::span<const std::byte> notes, int) {
          const TileFileNormals done = file_normals_result(result);
          ByteReader read(notes);
          const std::vector<std::uint64_t> index = read.get_array<std::uint64_t>();
          const std::vector<vec3> unit = read.get_array<vec3>();
          const std::vector<vec3> at = read.get_array<vec3>();
          if (unit.size() != index.size() || at.size() != index.size())
            throw Error("a tile's file normals do not hold together");
          for (std::size_t k = 0; k < done.sample.size(); ++k) {
            const auto i = std::size_t(done.sample[k]);
            if (i >= index.size()) throw Error("a tile's file normals do not hold together");
            directed = directed && has_direction(done.normal[k]);
            off += done.off[k] != 0;
            ++samples;
            const Oriented r{index[i], at[i], done.normal[k], 0, ProjectionStatus::converged, true};
            by_tile->append(t, &r);
            moved[std::size_t(t)] = std::max(moved[std::size_t(t)], double(glm::length(at[i] - unit[i])));
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
  out.normals.pieces = {{0}, {0}, {0}};
  out.turned = turn_seams_in_tiles(sets, out.normals, farm);
  if (face_as_seen_in_tiles(sets, kappa, moved, window_points, folder, buffer_bytes, farm, out.normals) > 0) {
    out.turned = 0;  // counted anew: those that face against the file's
    for (int t = 0; t < cloud.tiles(); ++t)
      out.normals.by_tile->for_each_record<Oriented>(t,
                                                     [&](const Oriented& r) { out.turned += out.normals.turned(r); });
  }
  return out;
}

}  // namespace pss
