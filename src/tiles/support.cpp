#include "pss/tiles/support.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "pss/core/error.hpp"
#include "pss/core/median.hpp"
#include "pss/core/progress.hpp"
#include "pss/points/support_steps.hpp"
#include "pss/points/unit_frame.hpp"
#include "halo_guess.hpp"
#include "tile_works.hpp"

namespace pss {

namespace {

// A tile and its halo in the unit frame, with each sample's margin: the set holds every
// point of the cloud within it (a point outside the halo lies farther than the halo from
// the box), a little less for the rounding of the unit frame's floats.
struct HaloTile {
  TilePoints points;
  std::vector<vec3> unit;
  std::vector<float> margin;  // empty when the tile and its halo hold the whole cloud
  MarginTile view(std::uint64_t cloud_size, double scale) const {
    return MarginTile{unit, points.index, margin, points.own, cloud_size, scale};
  }
};

HaloTile load_unit(const TiledCloud& cloud, int tile, float halo, const UnitFrame& frame) {
  HaloTile t{cloud.load(tile, halo), {}, {}};
  t.unit.resize(t.points.positions.size());
  for (std::size_t i = 0; i < t.unit.size(); ++i) t.unit[i] = frame.to_unit(t.points.positions[i]);
  if (t.points.positions.size() < cloud.size()) {
    const Aabb box = cloud.tile_box(tile);
    t.margin.resize(t.unit.size());
    for (std::size_t i = 0; i < t.unit.size(); ++i)
      t.margin[i] = float((double(halo) - distance_to_box(t.points.positions[i], box)) / frame.scale *
                          (1 - 1e-5));
  }
  return t;
}

// Each tile with points worked on by the farm with the halo that the tiles before it needed
// (halo_guess.hpp), and where its result says the halo did not hold every answer its own
// samples read, here again with the halo doubling until it does. request(tile) is a tile's
// work; use(its own points' indices, result) takes the result, or says it is incomplete.
template <class Request, class Use>
void for_each_tile(const TiledCloud& cloud, const UnitFrame& frame, TileFarm& farm, TileStep step, Progress& progress,
                   Request&& request, Use&& use) {
  const auto width = [&](int t) {
    const Aabb box = cloud.tile_box(t);
    return box.hi.x - box.lo.x;
  };
  HaloGuess guess;
  std::vector<float> first_halo(std::size_t(cloud.tiles()), 0.0f);  // each tile's, as it was asked
  farm.run(
      step, cloud.tiles_with_points(),
      [&](int t) {
        first_halo[std::size_t(t)] = guess.first(width(t));
        const HaloTile tile = load_unit(cloud, t, first_halo[std::size_t(t)], frame);
        return TileRequest{request(tile), own_points_notes(tile.points)};
      },
      [&](int t, std::span<const std::byte> result, std::span<const std::byte> notes, int) {
        const std::vector<std::uint64_t> own = own_points(notes);
        std::vector<std::byte> wider;
        float halo = first_halo[std::size_t(t)];
        while (!use(own, result)) {
          halo *= 2;
          wider = tile_work(step, request(load_unit(cloud, t, halo, frame)));
          result = wider;
        }
        guess.held(halo, width(t));
        progress.advance(std::int64_t(cloud.tile_size(t)));
      });
}

}  // namespace

SupportWidths support_widths(const TiledCloud& cloud, const ProjectionParams& params, TileFarm& farm) {
  const float h = params.h;
  if (!(h > 0) || !std::isfinite(h)) throw Error("h must be a positive number (got " + std::to_string(h) + ")");
  const std::uint64_t n = cloud.size();
  SupportWidths out;
  out.least = out.median = out.largest = h;
  out.h.assign(std::size_t(n), h);
  if (params.support == Support::global || n < 2) return out;
  const UnitFrame frame = cloud.unit_frame();
  const std::size_t stride = noise_query_stride(std::size_t(n));
  const std::size_t queries = std::size_t((n + stride - 1) / stride);

  // The first pass: each sample's spacing, and σ at the noise queries.
  std::vector<float> spacing(std::size_t(n), 0.0f), least(std::size_t(n), 0.0f);
  std::vector<vec3> at(queries);
  std::vector<float> measured(queries);
  std::uint64_t row_like = 0;
  {
    Progress progress("support widths (spacing)", std::int64_t(n));
    for_each_tile(
        cloud, frame, farm, TileStep::spacing, progress,
        [&](const HaloTile& tile) { return spacing_request(tile.view(n, frame.scale), stride); },
        [&](const std::vector<std::uint64_t>& own, std::span<const std::byte> result) {
          const TileSpacing s = spacing_result(result, own.size());
          if (!s.complete) return false;
          for (std::size_t i = 0; i < own.size(); ++i) {
            spacing[std::size_t(own[i])] = s.spacing[i];
            least[std::size_t(own[i])] = s.least[i];
          }
          row_like += s.row_like;
          for (std::size_t q = 0; q < s.query.size(); ++q) {
            if (s.query[q] >= queries) throw Error("a tile's spacings do not hold together");
            at[std::size_t(s.query[q])] = s.at[q];
            measured[std::size_t(s.query[q])] = s.measured[q];
          }
          return true;
        });
  }
  // As rows.hpp's first test: the in-core widths look for rows only where it holds.
  if (2 * row_like >= n)
    throw NotTiled("the cloud is sampled in rows (most samples' neighbours lie along a curve): its adaptive widths are "
                "worked out in core only");
  const float median_d = median_of(spacing);
  if (!(median_d > 0)) return out;  // most samples coincide with k others: no spacing to follow
  const float widest = widest_width(h, params, frame.diagonal);

  // The second pass: which samples widen, and each width, from the first's spacings; which
  // are merged.
  std::vector<char> merged(std::size_t(n), 0);
  Progress progress("support widths", std::int64_t(n));
  for_each_tile(
      cloud, frame, farm, TileStep::widths, progress,
      [&](const HaloTile& tile) {
        std::vector<float> set_spacing(tile.unit.size()), set_least(tile.unit.size());
        for (std::size_t i = 0; i < tile.unit.size(); ++i) {
          set_spacing[i] = spacing[std::size_t(tile.points.index[i])];
          set_least[i] = least[std::size_t(tile.points.index[i])];
        }
        return widths_request(tile.view(n, frame.scale), {set_spacing, set_least, median_d, h, widest, params.rho / params.h, at, measured});
      },
      [&](const std::vector<std::uint64_t>& own, std::span<const std::byte> result) {
        const TileWidths w = widths_result(result, own.size());
        if (!w.complete) return false;
        for (std::size_t i = 0; i < own.size(); ++i) {
          out.h[std::size_t(own[i])] = w.h[i];
          merged[std::size_t(own[i])] = w.merged[i];
        }
        return true;
      });
  take_merged(out, std::move(merged));
  out.least = *std::min_element(out.h.begin(), out.h.end());
  out.largest = *std::max_element(out.h.begin(), out.h.end());
  out.median = median_of(out.h);
  return out;
}

}  // namespace pss
