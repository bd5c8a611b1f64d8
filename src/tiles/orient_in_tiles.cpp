#include "orient_in_tiles.hpp"

#include <algorithm>
#include <memory>
#include <utility>

#include "pss/core/error.hpp"
#include "pss/core/progress.hpp"
#include "pss/points/facing_vote.hpp"
#include "pss/points/visibility.hpp"
#include "tile_bytes.hpp"
#include "tile_works.hpp"

namespace pss {

namespace {

// The distance between two boxes (0 where they touch or overlap).
double box_distance(const Aabb& a, const Aabb& b) {
  return glm::length(glm::max(glm::max(glm::dvec3(a.lo) - glm::dvec3(b.hi), glm::dvec3(b.lo) - glm::dvec3(a.hi)),
                              glm::dvec3(0.0)));
}

// Where samples were merged, each record's sample's place among the records, −1 where it
// stands for itself, or kSampleNotInSet where its sample's point the set lacks (tile_works.hpp:
// orientation_request). Empty where none were merged.
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
    sample[i] = at != place.end() && at->first == r.sample && records[std::size_t(at->second)].stands_for_itself()
                    ? at->second
                    : kSampleNotInSet;
  }
  return sample;
}

// The pieces' votes: each halo point's normal against its own tile's, window by window.
void vote(const BucketFile& ordered, std::uint64_t n, std::size_t window_points, PieceSigns& signs) {
  for (int w = 0; w < ordered.buckets(); ++w) {
    const std::uint64_t first = std::uint64_t(w) * window_points;
    const std::size_t size = std::size_t(std::min<std::uint64_t>(window_points, n - first));
    std::vector<Oriented> own(size);
    auto each = [&](bool is_own, auto&& f) {
      ordered.for_each_record<Oriented>(w, [&](const Oriented& r) {
        if (r.own == is_own) f(r);
      });
    };
    each(true, [&](const Oriented& r) { own[r.index - first] = r; });
    each(false, [&](const Oriented& r) {
      const Oriented& o = own[r.index - first];
      signs.vote(r.piece, o.piece, glm::dot(r.normal, o.normal) >= 0, r.seen_turned, o.seen_turned);
    });
  }
}

// The whole cloud's samples' discs (visibility.hpp), marked tile by tile: those of the
// records that stand for themselves, as the in-core tree's points are.
Occupancy occupancy_of(const BucketFile& records, int tiles, Progress& progress) {
  Aabb box;
  for (int t = 0; t < tiles; ++t)
    records.for_each_record<Projected>(t, [&](const Projected& r) {
      if (r.stands_for_itself() && is_finite(r.point)) box.grow(r.point);
    });
  Occupancy occupancy(box);
  for (int t = 0; t < tiles; ++t) {
    std::vector<vec3> points, normals;
    std::vector<float> radius;
    records.for_each_record<Projected>(t, [&](const Projected& r) {
      if (!r.stands_for_itself()) return;
      points.push_back(r.point);
      normals.push_back(r.normal);
      radius.push_back(visibility_radius(r.radius));
    });
    occupancy.mark(points, normals, radius);
    progress.advance(std::int64_t(records.records(t)));
  }
  return occupancy;
}

struct Set {  // a tile's records and its halo's: its notes
  std::vector<Projected> records;
  std::size_t own = 0;
};

}  // namespace

OrientedInTiles orient_in_tiles(const OrientationInputs& in, std::size_t window_points, bool by_tile,
                                const std::filesystem::path& folder, std::size_t buffer_bytes, TileFarm& farm,
                                const char* label) {
  const TiledCloud& cloud = in.cloud;
  const std::uint64_t n = cloud.size();
  const std::size_t windows = std::size_t((n + window_points - 1) / window_points);
  // Two files take records at once where both are asked: the buffers share the budget.
  const std::size_t buffer = by_tile ? buffer_bytes / 2 : buffer_bytes;
  OrientedInTiles out;
  out.ordered = std::make_unique<BucketFile>(folder, int(std::max<std::size_t>(windows, 1)), sizeof(Oriented), buffer);
  if (by_tile) out.by_tile = std::make_unique<BucketFile>(folder, cloud.tiles(), sizeof(Oriented), buffer);
  PieceSigns signs;
  std::uint64_t records = 0;  // each own record once: a point each, or a sample each
  for (int t = 0; t < cloud.tiles(); ++t) records += in.records.records(t);
  Progress progress(label, 2 * std::int64_t(records));  // the discs marked, then the tiles oriented
  auto occupancy = std::make_unique<const Occupancy>(occupancy_of(in.records, cloud.tiles(), progress));
  const double farthest = in.moved.empty() ? 0.0 : *std::max_element(in.moved.begin(), in.moved.end());
  farm.run(
      TileStep::orientation, cloud.tiles_with_points(),
      [&](int t) {
        // Each own point lies within moved[t] of the box and links to points within the
        // widest ρ_j of it; a point of tile u lies within moved[u] of u's box.
        const double reach_t = in.reach + in.moved[std::size_t(t)];
        const double halo = world_halo(reach_t, in.frame);
        const Aabb box = cloud.tile_box(t);
        Set set;
        in.records.for_each_record<Projected>(t, [&](const Projected& r) { set.records.push_back(r); });
        set.own = set.records.size();
        for (const int u : cloud.tiles_near(t, float(world_halo(reach_t + farthest, in.frame)))) {
          if (box_distance(cloud.tile_box(u), box) > world_halo(reach_t + in.moved[std::size_t(u)], in.frame)) continue;
          in.records.for_each_record<Projected>(u, [&](const Projected& r) {
            if (distance_to_box(in.frame.from_unit(r.point), box) <= halo) set.records.push_back(r);
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
        return TileRequest{
            orientation_request(points, normals, radius, id, *occupancy, samples_in_set(set.records, in.merged)),
            notes.take()};
      },
      [&](int t, std::span<const std::byte> result, std::span<const std::byte> notes, int) {
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
        std::vector<PieceRays> rays(parts.root.size());
        for (std::size_t i = 0; i < set.own; ++i) {
          const Projected& r = set.records[i];
          if (!r.stands_for_itself()) continue;  // in core the tree's points vote
          const auto p = std::size_t(parts.of_point[i]);
          const vec3 n = oriented.normals[i];
          const float inv_rho2 = 1.0f / (r.radius * r.radius);
          vote[p].add(r.point, n, inv_rho2, r.status);
          rays[p].seen_facing.add(r.point, oriented.seen_turned[i] ? -n : n, inv_rho2, r.status);
          const std::int8_t seen = oriented.seen_votes[i];  // with the rays' signs
          rays[p].points += 1;
          rays[p].voters += seen != 0;
          rays[p].seen_sum += seen;
        }
        std::vector<std::uint32_t> piece(parts.root.size(), kNoPiece);
        for (std::size_t p = 0; p < piece.size(); ++p) {
          const Projected& root = set.records[std::size_t(parts.root[p])];
          if (size[p] > 1 || std::size_t(parts.root[p]) < set.own)
            piece[p] = signs.add_piece(root.point.z, root.index, vote[p], rays[p]);
        }
        for (std::size_t i = 0; i < set.records.size(); ++i) {
          const std::uint32_t p = piece[std::size_t(parts.of_point[i])];
          if (p == kNoPiece) continue;
          const Projected& r = set.records[i];
          const Oriented o{r.index, r.point, oriented.normals[i], p, r.status, i < set.own,
                           oriented.seen_turned[i] != 0};
          out.ordered->append(int(r.index / window_points), &o);
          if (out.by_tile && o.own) out.by_tile->append(t, &o);
        }
        progress.advance(std::int64_t(set.own));
      });
  occupancy.reset();
  out.ordered->flush();
  if (out.by_tile) out.by_tile->flush();
  vote(*out.ordered, n, window_points, signs);
  out.pieces = signs.turns();
  return out;
}

}  // namespace pss
