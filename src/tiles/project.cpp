#include "pss/tiles/project.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "pss/core/error.hpp"
#include "pss/core/memory.hpp"
#include "pss/core/progress.hpp"
#include "pss/points/merged_samples.hpp"
#include "pss/points/outliers.hpp"
#include "pss/tiles/orient.hpp"
#include "pss/tiles/support.hpp"
#include "tile_bytes.hpp"
#include "tile_works.hpp"

namespace pss {

namespace {

// Records written whole to scratch files: every byte set, padding included.
struct Projected {  // a point projected, in its tile's bucket
  std::uint64_t index;
  std::uint64_t sample;  // the point its sample stands at (itself, unmerged), or kNoSample
  vec3 point, normal;  // unit frame
  float radius;        // ρ_i, unit frame: the orientation links the samples of each N(p_i)
  ProjectionStatus status;
  std::uint8_t unused[3] = {};
  // Whether the point stands for itself in the orientation: a sample's own point, or a point
  // of no sample (set aside), as in core (project_cloud.cpp).
  bool stands_for_itself() const;
};
static_assert(sizeof(Projected) == 48);

constexpr std::uint64_t kNoSample = std::uint64_t(-1);

bool Projected::stands_for_itself() const { return sample == index || sample == kNoSample; }

struct Oriented {  // a point oriented, in its window's bucket: its own tile's, or a halo's vote
  std::uint64_t index;
  vec3 point, normal;  // unit frame
  std::uint32_t piece;
  ProjectionStatus status;
  bool own;
  std::uint8_t unused[2] = {};
};
static_assert(sizeof(Oriented) == 40);

constexpr std::uint32_t kNoPiece = std::uint32_t(-1);

// A tile and its halo in the unit frame, with each point's width and whether it is a sample.
struct UnitSet {
  TilePoints points;
  std::vector<vec3> unit;
  std::vector<float> h;
  std::vector<int> samples;  // indices into the set of the samples kept
  std::vector<vec3> sample_at;  // where samples were merged: UnitTile's
  std::vector<int> into;
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
  UnitSet s{cloud.load(tile, float(halo)), {}, {}, {}, {}, {}};
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
  return s;
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

// The world halo that holds every sample within `unit_reach` of the tile's box: a little more
// for the rounding of the unit frame's floats (about 2^-25 of the box, whatever the reach).
double world_halo(double unit_reach, const UnitFrame& frame) {
  return (unit_reach + 0x1p-20) * frame.scale * (1 + 1e-5);
}

// The distance between two boxes (0 where they touch or overlap).
double box_distance(const Aabb& a, const Aabb& b) {
  return glm::length(glm::max(glm::max(glm::dvec3(a.lo) - glm::dvec3(b.hi), glm::dvec3(b.lo) - glm::dvec3(a.hi)),
                              glm::dvec3(0.0)));
}

UnitTile unit_tile(const UnitSet& set) {
  return {set.unit, set.h, set.samples, set.points.own, set.sample_at, set.into};
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
std::vector<char> samples_kept(const TiledCloud& cloud, const UnitFrame& frame, const std::vector<float>& h,
                               std::span<const char> merge, float kappa, double halo, TileFarm& farm,
                               OutlierReport& report) {
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
          const UnitSet set = load_unit(cloud, t, world_halo(halo, frame), frame, h, kept, merge);
          return TileRequest{outliers_request(unit_tile(set), kappa), own_points_notes(set.points)};
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
  }
  return kept;
}

// Where samples were merged, each record's sample's place among the records, or −1 where it
// stands for itself (tile_works.hpp: orientation_request); a point whose sample's point the
// set lacks stands for itself. Empty where none were merged.
std::vector<int> samples_in_set(const std::vector<Projected>& records, bool merged) {
  if (!merged) return {};
  std::vector<std::pair<std::uint64_t, int>> place(records.size());
  for (std::size_t i = 0; i < records.size(); ++i) place[i] = {records[i].index, int(i)};
  std::sort(place.begin(), place.end());
  std::vector<int> sample(records.size(), -1);
  for (std::size_t i = 0; i < records.size(); ++i) {
    const Projected& r = records[i];
    if (r.stands_for_itself()) continue;
    const auto at = std::lower_bound(place.begin(), place.end(), std::pair<std::uint64_t, int>(r.sample, -1));
    if (at != place.end() && at->first == r.sample && records[std::size_t(at->second)].stands_for_itself())
      sample[i] = at->second;
  }
  return sample;
}

// The pieces' votes: each halo point's normal against its own tile's, window by window.
void vote(const BucketFile& ordered, std::uint64_t n, std::size_t window_points, PieceSigns& signs) {
  for (int w = 0; w < ordered.buckets(); ++w) {
    const std::uint64_t first = std::uint64_t(w) * window_points;
    const std::size_t size = std::size_t(std::min<std::uint64_t>(window_points, n - first));
    std::vector<vec3> normal(size);
    std::vector<std::uint32_t> piece(size);
    auto each = [&](bool own, auto&& f) {
      ordered.for_each_record<Oriented>(w, [&](const Oriented& r) {
        if (r.own == own) f(r);
      });
    };
    each(true, [&](const Oriented& r) {
      normal[r.index - first] = r.normal;
      piece[r.index - first] = r.piece;
    });
    each(false, [&](const Oriented& r) {
      signs.vote(r.piece, piece[r.index - first], glm::dot(r.normal, normal[r.index - first]) >= 0);
    });
  }
}

}  // namespace

TiledProjection::TiledProjection(const TiledCloud& cloud, const ProjectionParams& params, Backend backend,
                                 const std::filesystem::path& folder, std::size_t window_points,
                                 std::size_t buffer_bytes, Stats& stats, TileFarm& farm)
    : cloud_(cloud), window_points_(std::max<std::size_t>(window_points, 1)) {
  validate(params);
  check_tiled_surface(params.surface);
  // The file's normals orient MLS's and are fitted by APSS and RIMLS, after their flips are
  // turned over the whole cloud (turn_flipped_normals.hpp); --normals estimate leaves them out,
  // as in core.
  if (cloud.has_normals() && params.normals == NormalSource::file)
    throw NotTiled("tile by tile, pss project does not take a file's normals so far (--normals estimate leaves them "
                   "out)");
  const std::uint64_t n = cloud.size();
  frame_ = unit_frame_of_box(glm::dvec3(cloud.bounds().lo), glm::dvec3(cloud.bounds().hi));
  check_neighbourhood(params, frame_.diagonal);
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
  if (params.outliers == OutlierPolicy::set_aside) {
    ScopedPhase phase(stats, "outliers", false);  // its Progress shows it
    kept = samples_kept(cloud, frame_, h, merge, kappa, halo, farm, outliers_);
  }

  // The projections, each tile's from its samples and its halo's (tile_works.hpp). How far
  // each tile's points moved says how far its projections lie outside its box.
  BucketFile projected(folder, cloud.tiles(), sizeof(Projected), buffer_bytes);
  std::vector<double> moved(std::size_t(cloud.tiles()), 0.0);  // the farthest, unit frame
  points_per_rank_.assign(std::size_t(farm.ranks()), 0);
  {
    ScopedPhase phase(stats, "projection", false);  // its Progress shows it
    Progress progress("projecting", std::int64_t(n));
    farm.run(
        TileStep::projection, cloud.tiles_with_points(),
        [&](int t) {
          const UnitSet set = load_unit(cloud, t, world_halo(halo, frame_), frame_, h, kept, merge);  // N(r) of each point
          ByteWriter notes;  // the own points' indices, unit positions and samples
          notes.put_array(std::span(set.points.index).first(set.points.own));
          notes.put_array(std::span<const vec3>(set.unit).first(set.points.own));
          notes.put_array(std::span<const std::uint64_t>(own_samples(set, kept)));
          return TileRequest{projection_request(unit_tile(set), kappa, unit_params, backend), notes.take()};
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
            const Projected r{index[i], sample[i], p.point, p.normal, kappa * h[std::size_t(index[i])], p.status};
            projected.append(t, &r);
            counts_.add(r.status);
          }
          points_per_rank_[std::size_t(rank)] += count;
          progress.advance(std::int64_t(count));
        });
  }
  projected.flush();
  release(h);
  release(kept);
  release(merge);

  // The orientation (orient_normals.hpp), tile by tile: each tile's points with those of its
  // halo, every point linked to those within their ρ_j; each piece of it a sign to agree on.
  const std::size_t windows = std::size_t((n + window_points_ - 1) / window_points_);
  ordered_ = std::make_unique<BucketFile>(folder, int(std::max<std::size_t>(windows, 1)), sizeof(Oriented), buffer_bytes);
  PieceSigns signs;
  ScopedPhase orientation(stats, "orient normals", false);  // its Progress shows it
  {
    Progress progress("orient normals", std::int64_t(n));
    const double farthest = *std::max_element(moved.begin(), moved.end());
    struct Set {  // a tile's projected points and its halo's: its notes
      std::vector<Projected> records;
      std::size_t own = 0;
    };
    farm.run(
        TileStep::orientation, cloud.tiles_with_points(),
        [&](int t) {
          // Each own point lies within moved[t] of the box and links to points within the
          // widest ρ_j of it; a point of tile u lies within moved[u] of u's box.
          const double reach_t = reach + moved[std::size_t(t)];
          const double halo = world_halo(reach_t, frame_);
          const Aabb box = cloud.tile_box(t);
          Set set;
          projected.for_each_record<Projected>(t, [&](const Projected& r) { set.records.push_back(r); });
          set.own = set.records.size();
          for (const int u : cloud.tiles_near(t, float(world_halo(reach_t + farthest, frame_)))) {
            if (box_distance(cloud.tile_box(u), box) > world_halo(reach_t + moved[std::size_t(u)], frame_)) continue;
            projected.for_each_record<Projected>(u, [&](const Projected& r) {
              if (distance_to_box(frame_.from_unit(r.point), box) <= halo) set.records.push_back(r);
            });
          }
          std::sort(set.records.begin() + std::ptrdiff_t(set.own), set.records.end(),
                    [](const Projected& a, const Projected& b) { return a.index < b.index; });
          const std::size_t m = set.records.size();
          std::vector<vec3> points(m), normals(m);
          std::vector<float> radius(m);
          std::vector<std::uint64_t> id(m);
          for (std::size_t i = 0; i < m; ++i) {
            points[i] = set.records[i].point;
            normals[i] = set.records[i].normal;
            radius[i] = set.records[i].radius;
            id[i] = set.records[i].index;
          }
          ByteWriter notes;
          notes.put(std::uint64_t(set.own));
          notes.put_array(std::span<const Projected>(set.records));
          return TileRequest{orientation_request(points, normals, radius, id, samples_in_set(set.records, widths_.merged_count > 0)),
                             notes.take()};
        },
        [&](int, std::span<const std::byte> result, std::span<const std::byte> notes, int) {
          ByteReader read(notes);
          Set set;
          set.own = std::size_t(read.get<std::uint64_t>());
          set.records = read.get_array<Projected>();
          if (set.own > set.records.size()) throw Error("a tile's orientation does not hold together");
          const TileOrientation oriented = orientation_result(result, set.records.size());
          const OrientedParts& parts = oriented.parts;
          // A halo's point alone in its part can only agree with its own tile's piece: no piece.
          std::vector<int> size(parts.root.size(), 0);
          for (const int part : parts.of_point) ++size[std::size_t(part)];
          std::vector<FacingVote> vote(parts.root.size());
          for (std::size_t i = 0; i < set.own; ++i) {
            const Projected& r = set.records[i];
            if (r.stands_for_itself())  // in core the tree's points vote
              vote[std::size_t(parts.of_point[i])].add(r.point, oriented.normals[i], 1.0f / (r.radius * r.radius), r.status);
          }
          std::vector<std::uint32_t> piece(parts.root.size(), kNoPiece);
          for (std::size_t p = 0; p < piece.size(); ++p) {
            const Projected& root = set.records[std::size_t(parts.root[p])];
            if (size[p] > 1 || std::size_t(parts.root[p]) < set.own)
              piece[p] = signs.add_piece(root.point.z, root.index, vote[p]);
          }
          for (std::size_t i = 0; i < set.records.size(); ++i) {
            const std::uint32_t p = piece[std::size_t(parts.of_point[i])];
            if (p == kNoPiece) continue;
            const Projected& r = set.records[i];
            const Oriented o{r.index, r.point, oriented.normals[i], p, r.status, i < set.own};
            ordered_->append(int(r.index / window_points_), &o);
          }
          progress.advance(std::int64_t(set.own));
        });
  }
  ordered_->flush();

  vote(*ordered_, n, window_points_, signs);
  flip_ = signs.turns();
}

void check_tiled_surface(SurfaceOperator surface) {
  if (surface != SurfaceOperator::mls)
    throw NotTiled("tile by tile, pss project fits the paper's MLS surface only (not APSS or RIMLS) so far");
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
