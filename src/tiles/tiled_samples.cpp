#include "tiled_samples.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "pss/core/error.hpp"
#include "pss/core/progress.hpp"
#include "pss/points/merged_samples.hpp"
#include "pss/points/sample_normals.hpp"
#include "pss/tiles/support.hpp"
#include "tile_bytes.hpp"
#include "tile_records.hpp"

namespace pss {

namespace {

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
  const auto in_cloud_order = [&](int a, int b) {
    return s.points.index[std::size_t(a)] < s.points.index[std::size_t(b)];
  };
  std::sort(s.samples.begin(), s.samples.end(), in_cloud_order);
  return s;
}


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

// APSS's and RIMLS's samples' normals (points/sample_normals.hpp) tile by tile, as in core:
// each own sample's WLS plane at its place (a merged one at its cube's mean), then oriented
// over the tiles as the projections' normals are, linked within the samples' ρ_i (the seams'
// turn follows: turn_seams_in_tiles).
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
          const std::vector<vec3>& places = set.sample_at.empty() ? set.unit : set.sample_at;
          notes.put_array(std::span<const vec3>(places).first(set.points.own));
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



}  // namespace

UnitSet UnitSets::load(int tile) const {
  UnitSet set = load_unit(cloud, tile, world_halo(halo, frame), frame, h, kept, merge);
  set.layout = &layout;
  return set;
}

// The places the grid is built of: where samples merged, each cube's first point at its mean.
const std::vector<vec3>& grid_places(const UnitSet& s) { return s.sample_at.empty() ? s.unit : s.sample_at; }

UnitTile unit_tile(const UnitSet& set) {
  return {set.unit, set.h, set.samples, set.points.own, set.sample_at, set.into, set.normals, set.layout};
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

TiledSamples tiled_samples(const TiledCloud& cloud, const ProjectionParams& params, bool with_normals,
                           Backend backend, std::size_t window_points, const std::filesystem::path& folder,
                           std::size_t buffer_bytes, Stats& stats, TileFarm& farm) {
  TiledSamples s;
  const std::uint64_t n = cloud.size();
  s.frame = cloud.unit_frame();
  check_neighbourhood(params, s.frame.diagonal, n);
  s.unit_params = in_unit_frame(params, s.frame.scale);
  s.kappa = s.unit_params.rho / s.unit_params.h;
  {
    ScopedPhase phase(stats, "support widths", params.support == Support::global);
    SupportWidths widths = support_widths(cloud, params, farm);
    s.widths = {{}, widths.least, widths.median, widths.largest, {}, widths.merged_count};
    s.h = std::move(widths.h);
    s.merge = std::move(widths.merged);
  }
  for (float& w : s.h) w = float(double(w) / s.frame.scale);
  s.reach = double(s.kappa) * (n > 0 ? *std::max_element(s.h.begin(), s.h.end()) : 0.0f);
  s.halo = merge_halo(s.reach, s.h, s.merge);
  s.kept.assign(std::size_t(n), 1);
  {
    ScopedPhase phase(stats, "support layout");
    s.layout = layout_in_tiles(cloud, s.frame, s.h, s.kept, s.merge, s.kappa, s.halo);
  }
  if (params.outliers == OutlierPolicy::set_aside) {
    ScopedPhase phase(stats, "outliers", false);  // its Progress shows it
    s.kept = samples_kept(cloud, s.frame, s.h, s.merge, s.kappa, s.halo, farm, s.outliers, s.layout);
  }
  if (params.normals == NormalSource::file) s.without_direction = cloud.normals_without_direction();
  if (cloud.has_normals() && params.normals == NormalSource::file) {
    ScopedPhase phase(stats, "file normals", false);  // its Progress shows it
    FileNormalsInTiles file = file_normals_in_tiles(s.sets(cloud), s.kappa, window_points, folder, buffer_bytes, farm);
    s.normals_turned = file.turned;
    s.file_normals_off = file.off_the_points;
    if (file.normals.by_tile) {
      s.normals = std::move(file.normals);
      s.normals_used = NormalsUsed::file;
    }
  }
  if (with_normals && !s.file_hints()) {
    ScopedPhase phase(stats, "sample normals", false);  // its Progress shows it
    s.normals = sample_normals_in_tiles(s.sets(cloud), s.kappa, s.unit_params, backend, window_points, folder,
                                        buffer_bytes, farm);
    s.normals.ordered.reset();  // its votes are counted
    turn_seams_in_tiles(s.sets(cloud), s.normals, farm);  // where the tree crossed a fold, as in core
    s.normals_used = NormalsUsed::estimated;
  }
  return s;
}

}  // namespace pss
