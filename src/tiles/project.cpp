#include "pss/tiles/project.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

#include "pss/core/error.hpp"
#include "pss/core/memory.hpp"
#include "pss/core/progress.hpp"
#include "pss/points/outliers.hpp"
#include "pss/tiles/memory_plan.hpp"
#include "tile_bytes.hpp"
#include "tile_records.hpp"
#include "tiled_samples.hpp"

namespace pss {

namespace {

// The point whose sample each own point of the set joined (Projected::sample).
std::vector<std::uint64_t> own_samples(const UnitSet& s, const std::vector<char>& kept) {
  std::vector<std::uint64_t> sample(s.points.own);
  for (std::size_t i = 0; i < s.points.own; ++i) {
    const std::uint64_t first = s.points.index[s.into.empty() ? i : std::size_t(s.into[i])];
    sample[i] = kept[std::size_t(first)] ? first : kNoSample;
  }
  return sample;
}

// APSS's and RIMLS's projections, and those the file's normals orient, are one piece, never
// turned (their normals follow the samples' oriented ones).
constexpr std::uint32_t kUnturned = 0;

}  // namespace

TiledProjection::TiledProjection(const TiledCloud& cloud, const ProjectionParams& params, Backend backend,
                                 const std::filesystem::path& folder, std::size_t window_points,
                                 std::size_t buffer_bytes, Stats& stats, TileFarm& farm)
    : cloud_(cloud), window_points_(std::max<std::size_t>(window_points, 1)) {
  validate(params);
  const std::uint64_t n = cloud.size();
  // APSS and RIMLS fit the samples' normals, the file's or estimated and oriented first, as in
  // core; the file's (their seams turned over the tiles) orient MLS's projections too. Then
  // the projections' normals follow those, and need no orientation of their own.
  const bool fits_normals = params.surface != SurfaceOperator::mls;
  TiledSamples prepared =
      tiled_samples(cloud, params, fits_normals, backend, window_points_, folder, buffer_bytes, stats, farm);
  frame_ = prepared.frame;
  widths_ = prepared.widths;
  outliers_ = prepared.outliers;
  if (fits_normals) normals_ = prepared.normals_used;
  normals_turned_ = prepared.normals_turned;
  file_normals_off_ = prepared.file_normals_off;
  without_direction_ = prepared.without_direction;
  const bool file_hints = prepared.file_hints();
  const bool follows_samples = fits_normals || file_hints;
  const ProjectionParams& unit_params = prepared.unit_params;
  const float kappa = prepared.kappa;
  std::vector<float>& h = prepared.h;
  std::vector<char>& kept = prepared.kept;
  std::vector<char>& merge = prepared.merge;
  const double reach = prepared.reach;
  const UnitSets sets = prepared.sets(cloud);  // N(r) of each point
  const OrientedInTiles& samples = prepared.normals;

  // The projections, each tile's from its samples and its halo's (tile_works.hpp). How far
  // each tile's points moved says how far its projections lie outside its box. MLS's wait by
  // tile for their orientation; APSS's and RIMLS's go to their windows.
  const std::size_t windows = std::size_t((n + window_points_ - 1) / window_points_);
  std::optional<BucketFile> projected;
  if (follows_samples)
    ordered_ = std::make_unique<BucketFile>(folder, int(std::max<std::size_t>(windows, 1)), sizeof(Oriented), buffer_bytes);
  else
    projected.emplace(folder, cloud.tiles(), sizeof(Projected), buffer_bytes);
  std::vector<double> moved(std::size_t(cloud.tiles()), 0.0);  // the farthest, unit frame
  points_per_rank_.assign(std::size_t(farm.ranks()), 0);
  {
    ScopedPhase phase(stats, "projection", false);  // its Progress shows it
    Progress progress("projecting", std::int64_t(n));
    farm.run(
        TileStep::projection, cloud.tiles_with_points(),
        [&](int t) {
          UnitSet set = sets.load(t);
          if (follows_samples) set.normals = normals_of_set(samples, sets, t, set);
          ByteWriter notes;  // the own points' indices, unit positions and samples
          notes.put_array(std::span<const std::uint64_t>(set.points.index).first(set.points.own));
          notes.put_array(std::span<const vec3>(set.unit).first(set.points.own));
          notes.put_array(std::span<const std::uint64_t>(own_samples(set, kept)));
          const std::span<const vec3> hints =
              file_hints ? std::span<const vec3>(set.points.normals) : std::span<const vec3>();
          return TileRequest{projection_request(unit_tile(set), unit_params, backend, hints), notes.take()};
        },
        [&](int t, std::span<const std::byte> result, std::span<const std::byte> notes, int rank) {
          const TileProjections done = projection_result(result);
          ByteReader read(notes);
          const std::vector<std::uint64_t> index = read.get_array<std::uint64_t>();
          const std::vector<vec3> unit = read.get_array<vec3>();
          const std::vector<std::uint64_t> sample = read.get_array<std::uint64_t>();
          const std::size_t count = index.size();
          if (done.order.size() != count || unit.size() != count || sample.size() != count)
            throw Error("a tile's projections do not hold together");
          for (std::size_t k = 0; k < count; ++k) {
            const auto i = std::size_t(done.order[k]);
            if (i >= count) throw Error("a tile's projections do not hold together");
            const ProjectedPoint& p = done.projected[k];
            moved[std::size_t(t)] = std::max(moved[std::size_t(t)], double(glm::length(p.point - unit[i])));
            if (follows_samples) {
              const Oriented o{index[i], p.point, p.normal, kUnturned, p.status, true};
              ordered_->append(int(index[i] / window_points_), &o);
            } else {
              const Projected r{index[i], sample[i], p.point, p.normal, kappa * h[std::size_t(index[i])], p.status};
              projected->append(t, &r);
            }
            counts_.add(p.status);
          }
          points_per_rank_[std::size_t(rank)] += count;
          progress.advance(std::int64_t(count));
        });
  }
  release(h);
  release(kept);
  release(merge);
  if (follows_samples) {
    ordered_->flush();
    pieces_.flip.assign(kUnturned + 1, 0);
    pieces_.seen.assign(kUnturned + 1, 0);
    return;
  }
  projected->flush();

  // The orientation (orient_normals.hpp), tile by tile (orient_in_tiles.hpp).
  ScopedPhase orientation(stats, "orient normals", false);  // its Progress shows it
  const OrientationInputs in{cloud, frame_, *projected, moved, reach, widths_.merged_count > 0};
  OrientedInTiles oriented = orient_in_tiles(in, window_points_, false, folder, buffer_bytes, farm, "orient normals");
  ordered_ = std::move(oriented.ordered);
  pieces_ = std::move(oriented.pieces);
}

void TiledProjection::read_in_order(const std::function<void(ProjectedWindow&)>& f) const {
  const std::uint64_t n = cloud_.size();
  for (int w = 0; w < ordered_->buckets() && n > 0; ++w) {
    ProjectedWindow window;
    window.first = std::uint64_t(w) * window_points_;
    const std::size_t size = std::size_t(std::min<std::uint64_t>(window_points_, n - window.first));
    window.positions.resize(size);
    window.normals.resize(size);
    window.status.resize(size);
    ordered_->for_each_record<Oriented>(w, [&](const Oriented& r) {
      if (!r.own) return;
      const std::size_t i = std::size_t(r.index - window.first);
      window.positions[i] = frame_.from_unit(r.point);
      window.normals[i] = pieces_(r.piece, r.seen_turned) ? -r.normal : r.normal;
      window.status[i] = r.status;
    });
    f(window);
  }
}

}  // namespace pss
