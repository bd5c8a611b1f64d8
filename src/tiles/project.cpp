#include "pss/tiles/project.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "pss/core/error.hpp"
#include "pss/core/memory.hpp"
#include "pss/core/progress.hpp"
#include "pss/points/merged_samples.hpp"
#include "pss/points/outliers.hpp"
#include "pss/tiles/support.hpp"
#include "orient_in_tiles.hpp"
#include "tile_bytes.hpp"
#include "tile_records.hpp"
#include "tile_works.hpp"

namespace pss {

namespace {

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

// The set's merged samples, as in core (merged_samples.hpp): each cube's points summed in the
// order of their indices in the cloud, the first of them standing for the cube. A cube is
// whole wherever its points lie within the halo; those of the samples within reach of the
// tile (and of the tile's samples' neighbourhoods) are, with a halo of two cubes' diagonals
// more (merge_halo).
void merge_in_set(UnitSet& s, std::span<const char> merge) {
  const std::size_t m = s.unit.size();
  std::vector<int> order(m);
  for (std::size_t i = 0; i < m; ++i) order[i] = int(i);
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    return s.points.index[std::size_t(a)] < s.points.index[std::size_t(b)];
  });
  std::vector<vec3> unit(m);
  std::vector<float> h(m);
  std::vector<char> marked(m);
  for (std::size_t k = 0; k < m; ++k) {
    const auto i = std::size_t(order[k]);
    unit[k] = s.unit[i];
    h[k] = s.h[i];
    marked[k] = merge[std::size_t(s.points.index[i])];
  }
  const MergedSamples merged = merge_samples(unit, h, marked);
  s.sample_at.resize(m);
  s.into.resize(m);
  for (std::size_t k = 0; k < m; ++k) {
    s.sample_at[std::size_t(order[k])] = merged.positions[k];
    s.into[std::size_t(order[k])] = order[std::size_t(merged.into[k])];
  }
}

// `kept` is each point's, and for a merged point its cube's first point's: whether its
// sample is kept (merged points other than a cube's first are no samples of their own).
UnitSet load_unit(const TiledCloud& cloud, int tile, double halo, const UnitFrame& frame,
                  const std::vector<float>& h, const std::vector<char>& kept, std::span<const char> merge) {
  UnitSet s{cloud.load(tile, float(halo)), {}, {}, {}, {}, {}, {}};
  const std::size_t m = s.points.positions.size();
  s.unit.resize(m);
  s.h.resize(m);
  for (std::size_t i = 0; i < m; ++i) {
    s.unit[i] = frame.to_unit(s.points.positions[i]);
    s.h[i] = h[std::size_t(s.points.index[i])];
  }
  if (!merge.empty()) merge_in_set(s, merge);
  for (std::size_t i = 0; i < m; ++i)
    if (kept[std::size_t(s.points.index[i])] && (s.into.empty() || s.into[i] == int(i))) s.samples.push_back(int(i));
  // In the cloud's order, as in core: ties within a grid's cell go by it (support_grid.hpp).
  const auto in_cloud_order = [&](int a, int b) { return s.points.index[std::size_t(a)] < s.points.index[std::size_t(b)]; };
  std::sort(s.samples.begin(), s.samples.end(), in_cloud_order);
  return s;
}

// The places the grid is built of: where samples merged, each cube's first point at its mean.
const std::vector<vec3>& grid_places(const UnitSet& s) { return s.sample_at.empty() ? s.unit : s.sample_at; }

// The whole cloud's layout of the samples `kept` (spatial/support_layout.hpp), the same as the
// in-core grid of those samples finds: tallied over each tile's own samples at their places
// in the grid (a merged one at its cube's mean, whole with merge_halo's halo; without merged
// samples no halo is read), their least width first.
SupportLayout layout_in_tiles(const TiledCloud& cloud, const UnitFrame& frame, const std::vector<float>& h,
                              const std::vector<char>& kept, std::span<const char> merge, float kappa, double halo) {
  const std::vector<int> tiles = cloud.tiles_with_points();
  const double read_halo = merge.empty() ? 0.0 : halo;
  const auto own_samples_of = [&](int t, const auto& f) {
    const UnitSet set = load_unit(cloud, t, world_halo(read_halo, frame), frame, h, kept, merge);
    for (const int i : set.samples)
      if (std::size_t(i) < set.points.own) f(grid_places(set)[std::size_t(i)], set.h[std::size_t(i)]);
  };
  SupportTally tally;
  tally.least = kInfinity;
  if (merge.empty()) {
    for (std::size_t i = 0; i < h.size(); ++i)
      if (kept[i]) tally.least = std::min(tally.least, h[i]);
  } else {
    for (const int t : tiles) own_samples_of(t, [&](vec3, float w) { tally.least = std::min(tally.least, w); });
  }
  for (const int t : tiles) {
    SupportTally own;
    own.least = tally.least;
    own_samples_of(t, [&](vec3 p, float w) { own.add(p, w); });
    tally.add(own);
  }
  return support_layout(tally, kappa);
}

// The point whose sample each own point of the set joined (Projected::sample).
std::vector<std::uint64_t> own_samples(const UnitSet& s, const std::vector<char>& kept) {
  std::vector<std::uint64_t> sample(s.points.own);
  for (std::size_t i = 0; i < s.points.own; ++i) {
    const std::uint64_t first = s.points.index[s.into.empty() ? i : std::size_t(s.into[i])];
    sample[i] = kept[std::size_t(first)] ? first : kNoSample;
  }
  return sample;
}

UnitTile unit_tile(const UnitSet& set) {
  return {set.unit, set.h, set.samples, set.points.own, set.sample_at, set.into, set.normals, set.layout};
}

// The unit halo that holds every sample within `reach` of a tile and, where samples merge,
// their cubes whole: a merged sample lies in its cube, within a diagonal of its points, and
// the outliers' pass measures a tile's own merged samples, whose cubes reach a diagonal out
// of the tile, against the cubes within reach of them.
double merge_halo(double reach, std::span<const float> h, std::span<const char> merge) {
  float widest = 0;
  for (std::size_t i = 0; i < merge.size(); ++i)
    if (merge[i]) widest = std::max(widest, h[i]);
  return reach + 2 * std::sqrt(3.0) * double(kMergeCell) * double(widest);
}

// The outliers' passes (points/outliers.hpp): each sample's distance in its tile, then the
// threshold over the whole cloud's, weighing merged samples by their masses as in core; whether
// each point is kept as a sample (for a merged point, its cube's first point's: load_unit).
// Each pass's grids take the layout of the samples it starts with, as in core; `layout`
// comes back that of the samples kept.
std::vector<char> samples_kept(const TiledCloud& cloud, const UnitFrame& frame, const std::vector<float>& h,
                               std::span<const char> merge, float kappa, double halo, TileFarm& farm,
                               OutlierReport& report, SupportLayout& layout) {
  const std::uint64_t n = cloud.size();
  const std::vector<int> tiles = cloud.tiles_with_points();
  std::vector<char> kept(std::size_t(n), 1);
  for (int pass = 0; pass < kOutlierPasses; ++pass) {
    std::vector<float> distance(std::size_t(n), std::numeric_limits<float>::quiet_NaN());
    std::vector<float> mass(merge.empty() ? 0 : std::size_t(n), 0.0f);
    std::vector<float> held(std::size_t(n), std::numeric_limits<float>::quiet_NaN());
    Progress progress("outliers", std::int64_t(n));
    farm.run(
        TileStep::outliers, tiles,
        [&](int t) {
          UnitSet set = load_unit(cloud, t, world_halo(halo, frame), frame, h, kept, merge);
          set.layout = &layout;
          return TileRequest{outliers_request(unit_tile(set)), own_points_notes(set.points)};
        },
        [&](int, std::span<const std::byte> result, std::span<const std::byte> notes, int) {
          const TileOutliers d = outliers_result(result);
          const std::vector<std::uint64_t> index = own_points(notes);
          if (d.distance.size() != index.size()) throw Error("a tile's outliers do not hold together");
          for (std::size_t i = 0; i < index.size(); ++i) {
            if (std::isnan(d.distance[i])) continue;
            distance[std::size_t(index[i])] = d.distance[i];
            held[std::size_t(index[i])] = d.held[i];
            if (!mass.empty()) mass[std::size_t(index[i])] = d.mass[i];
          }
          progress.advance(std::int64_t(index.size()));
        });
    if (pass == 0) {  // the second keeps them, as in core
      report.threshold = outlier_threshold(distance, mass);
      report.least_held = least_held(held, mass);
    }
    std::int64_t set_aside = 0;  // samples, a merged one once, as in core
    for (std::size_t i = 0; i < std::size_t(n); ++i)
      if (kept[i] && !std::isnan(distance[i]) && !on_the_surface(distance[i], held[i], report)) {
        kept[i] = 0;
        ++set_aside;
      }
    report.set_aside += set_aside;
    if (set_aside == 0) break;
    layout = layout_in_tiles(cloud, frame, h, kept, merge, kappa, halo);  // the next pass's grids, or the samples'
  }
  return kept;
}

// APSS's and RIMLS's projections are one piece, never turned (their normals follow the
// samples' oriented ones).
constexpr std::uint32_t kUnturned = 0;

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
  UnitSet load(int tile) const {
    UnitSet set = load_unit(cloud, tile, world_halo(halo, frame), frame, h, kept, merge);
    set.layout = &layout;
    return set;
  }
};

// APSS's and RIMLS's samples' normals (points/sample_normals.hpp) tile by tile, as in core:
// each own sample's WLS plane at its place (a merged one at its cube's mean), then oriented
// over the tiles as the projections' normals are, linked within the samples' ρ_i. Not yet as
// in core: the seams' turn after the orientation (turn_flipped_normals.hpp), so where it
// turns any sample's normal in core, the tiles' differ there (docs/architecture.md).
OrientedInTiles sample_normals_in_tiles(const UnitSets& sets, float kappa, const ProjectionParams& unit_params,
                                        Backend backend, std::size_t window_points, const std::filesystem::path& folder,
                                        std::size_t buffer_bytes, TileFarm& farm) {
  const TiledCloud& cloud = sets.cloud;
  BucketFile fitted(folder, cloud.tiles(), sizeof(Projected), buffer_bytes);
  std::vector<double> moved(std::size_t(cloud.tiles()), 0.0);  // a merged sample's place from its point
  {
    Progress progress("sample normals", std::int64_t(cloud.size()));
    farm.run(
        TileStep::sample_normals, cloud.tiles_with_points(),
        [&](int t) {
          const UnitSet set = sets.load(t);
          ByteWriter notes;  // the own points' indices, unit positions and places as samples
          notes.put_array(std::span(set.points.index).first(set.points.own));
          notes.put_array(std::span<const vec3>(set.unit).first(set.points.own));
          notes.put_array(std::span<const vec3>(set.sample_at.empty() ? set.unit : set.sample_at).first(set.points.own));
          return TileRequest{sample_normals_request(unit_tile(set), unit_params, backend), notes.take()};
        },
        [&](int t, std::span<const std::byte> result, std::span<const std::byte> notes, int) {
          const TileSampleNormals done = sample_normals_result(result);
          ByteReader read(notes);
          const std::vector<std::uint64_t> index = read.get_array<std::uint64_t>();
          const std::vector<vec3> unit = read.get_array<vec3>();
          const std::vector<vec3> at = read.get_array<vec3>();
          if (unit.size() != index.size() || at.size() != index.size())
            throw Error("a tile's sample normals do not hold together");
          for (std::size_t k = 0; k < done.sample.size(); ++k) {
            const auto i = std::size_t(done.sample[k]);
            if (i >= index.size()) throw Error("a tile's sample normals do not hold together");
            const Projected r{index[i], index[i], at[i], done.normal[k], kappa * sets.h[std::size_t(index[i])],
                              done.status[k]};
            fitted.append(t, &r);
            moved[std::size_t(t)] = std::max(moved[std::size_t(t)], double(glm::length(at[i] - unit[i])));
          }
          progress.advance(std::int64_t(index.size()));
        });
  }
  fitted.flush();
  const OrientationInputs in{cloud, sets.frame, fitted, moved, sets.reach, false};
  return orient_in_tiles(in, window_points, true, folder, buffer_bytes, farm, "orient sample normals");
}

// The oriented normals of the set's samples (UnitSet::normals), from the tiles that hold
// them: the tile's and those within the halo it was loaded with. Every sample within reach of
// the tile has one (its cube whole in the set: merge_halo); a merged sample beyond it may be
// a cube's part, whose first point in the set is no sample of the cloud: it reaches no point
// of the tile, and its normal is left zero.
std::vector<vec3> normals_of_set(const OrientedInTiles& samples, const UnitSets& sets, int tile, const UnitSet& set) {
  std::vector<std::pair<std::uint64_t, int>> wanted;  // each sample's index in the cloud, place in the set
  for (const int i : set.samples) wanted.push_back({set.points.index[std::size_t(i)], i});
  std::sort(wanted.begin(), wanted.end());
  std::vector<vec3> normals(set.unit.size(), vec3(0.0f));
  std::vector<char> found(set.unit.size(), 0);
  auto take = [&](int u) {
    samples.by_tile->for_each_record<Oriented>(u, [&](const Oriented& r) {
      const auto at = std::lower_bound(wanted.begin(), wanted.end(), std::pair<std::uint64_t, int>(r.index, -1));
      if (at == wanted.end() || at->first != r.index) return;
      normals[std::size_t(at->second)] = samples.turned(r) ? -r.normal : r.normal;
      found[std::size_t(at->second)] = 1;
    });
  };
  take(tile);
  for (const int u : sets.cloud.tiles_near(tile, float(world_halo(sets.halo, sets.frame)))) take(u);
  const Aabb box = sets.cloud.tile_box(tile);
  const std::vector<vec3>& at = set.sample_at.empty() ? set.unit : set.sample_at;
  for (const int i : set.samples)
    if (!found[std::size_t(i)] &&
        distance_to_box(sets.frame.from_unit(at[std::size_t(i)]), box) <= world_halo(sets.reach, sets.frame))
      throw Error("a tile's samples' normals do not hold together");
  return normals;
}

}  // namespace

TiledProjection::TiledProjection(const TiledCloud& cloud, const ProjectionParams& params, Backend backend,
                                 const std::filesystem::path& folder, std::size_t window_points,
                                 std::size_t buffer_bytes, Stats& stats, TileFarm& farm)
    : cloud_(cloud), window_points_(std::max<std::size_t>(window_points, 1)) {
  validate(params);
  // The file's normals orient MLS's and are fitted by APSS and RIMLS, after their flips are
  // turned over the whole cloud (turn_flipped_normals.hpp); --normals estimate leaves them out,
  // as in core.
  if (cloud.has_normals() && params.normals == NormalSource::file)
    throw NotTiled("tile by tile, pss project does not take a file's normals so far (--normals estimate leaves them "
                   "out)");
  const std::uint64_t n = cloud.size();
  frame_ = cloud.unit_frame();
  check_neighbourhood(params, frame_.diagonal, n);
  const ProjectionParams unit_params = in_unit_frame(params, frame_.scale);
  const float kappa = unit_params.rho / unit_params.h;

  // The widths, in the unit frame as in core.
  std::vector<float> h;
  std::vector<char> merge;  // empty, or whether each point merges (points/merged_samples.hpp)
  {
    ScopedPhase phase(stats, "support widths", params.support == Support::global);
    SupportWidths widths = support_widths(cloud, params, farm);
    widths_ = {{}, widths.least, widths.median, widths.largest, {}, widths.merged_count};
    h = std::move(widths.h);
    merge = std::move(widths.merged);
  }
  for (float& w : h) w = float(double(w) / frame_.scale);
  const double reach = double(kappa) * (n > 0 ? *std::max_element(h.begin(), h.end()) : 0.0f);  // the widest ρ_i
  const double halo = merge_halo(reach, h, merge);

  std::vector<char> kept(std::size_t(n), 1);
  SupportLayout layout;  // of the samples, as the in-core grid's (spatial/support_layout.hpp)
  {
    ScopedPhase phase(stats, "support layout");
    layout = layout_in_tiles(cloud, frame_, h, kept, merge, kappa, halo);
  }
  if (params.outliers == OutlierPolicy::set_aside) {
    ScopedPhase phase(stats, "outliers", false);  // its Progress shows it
    kept = samples_kept(cloud, frame_, h, merge, kappa, halo, farm, outliers_, layout);
  }

  // APSS and RIMLS fit the samples' normals, estimated and oriented first, as in core; their
  // projections' normals follow those, so they need no orientation of their own.
  const UnitSets sets{cloud, frame_, h, kept, merge, reach, halo, layout};  // N(r) of each point
  const bool fits_normals = params.surface != SurfaceOperator::mls;
  OrientedInTiles samples;
  if (fits_normals) {
    ScopedPhase phase(stats, "sample normals", false);  // its Progress shows it
    samples = sample_normals_in_tiles(sets, kappa, unit_params, backend, window_points_, folder, buffer_bytes, farm);
    samples.ordered.reset();  // its votes are counted
    normals_ = NormalsUsed::estimated;
  }

  // The projections, each tile's from its samples and its halo's (tile_works.hpp). How far
  // each tile's points moved says how far its projections lie outside its box. MLS's wait by
  // tile for their orientation; APSS's and RIMLS's go to their windows.
  const std::size_t windows = std::size_t((n + window_points_ - 1) / window_points_);
  std::optional<BucketFile> projected;
  if (fits_normals)
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
          if (fits_normals) set.normals = normals_of_set(samples, sets, t, set);
          ByteWriter notes;  // the own points' indices, unit positions and samples
          notes.put_array(std::span<const std::uint64_t>(set.points.index).first(set.points.own));
          notes.put_array(std::span<const vec3>(set.unit).first(set.points.own));
          notes.put_array(std::span<const std::uint64_t>(own_samples(set, kept)));
          return TileRequest{projection_request(unit_tile(set), unit_params, backend), notes.take()};
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
            if (fits_normals) {
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
  if (fits_normals) {
    ordered_->flush();
    flip_.assign(kUnturned + 1, 0);
    return;
  }
  projected->flush();

  // The orientation (orient_normals.hpp), tile by tile (orient_in_tiles.hpp).
  ScopedPhase orientation(stats, "orient normals", false);  // its Progress shows it
  const OrientationInputs in{cloud, frame_, *projected, moved, reach, widths_.merged_count > 0};
  OrientedInTiles oriented = orient_in_tiles(in, window_points_, false, folder, buffer_bytes, farm, "orient normals");
  ordered_ = std::move(oriented.ordered);
  flip_ = std::move(oriented.flip);
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
      window.normals[i] = flip_[r.piece] ? -r.normal : r.normal;
      window.status[i] = r.status;
    });
    f(window);
  }
}

}  // namespace pss
