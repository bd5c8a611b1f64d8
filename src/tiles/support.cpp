#include "pss/tiles/support.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "pss/backend/cpu/parallel_for.hpp"
#include "pss/core/error.hpp"
#include "pss/core/median.hpp"
#include "pss/core/progress.hpp"
#include "pss/points/support_steps.hpp"
#include "pss/points/unit_frame.hpp"
#include "pss/spatial/uniform_grid.hpp"

namespace pss {

namespace {

// A tile and its halo in the unit frame, with each sample's margin: the set holds every
// point of the cloud within it (a point outside the halo lies farther than the halo from
// the box), a little less for the rounding of the unit frame's floats.
struct UnitTile {
  TilePoints points;
  std::vector<vec3> unit;
  std::vector<float> margin;  // empty when the tile and its halo hold the whole cloud
  SampleSet set(std::uint64_t cloud_size, double scale) const {
    return SampleSet{unit, points.index, margin, cloud_size, scale};
  }
};

UnitTile load_unit(const TiledCloud& cloud, int tile, float halo, const UnitFrame& frame) {
  UnitTile t{cloud.load(tile, halo), {}, {}};
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

// f(tile, its points) for every tile with points, with the smallest halo (from an eighth of a
// tile, doubling) for which f says every own sample's answer is complete.
template <class F>
void for_each_tile(const TiledCloud& cloud, const UnitFrame& frame, Progress& progress, F&& f) {
  for (int t = 0; t < cloud.tiles(); ++t) {
    if (cloud.tile_size(t) == 0) continue;
    const Aabb box = cloud.tile_box(t);
    for (float halo = 0.125f * (box.hi.x - box.lo.x);; halo *= 2)
      if (f(load_unit(cloud, t, halo, frame))) break;
    progress.advance(std::int64_t(cloud.tile_size(t)));
  }
}

}  // namespace

SupportWidths support_widths(const TiledCloud& cloud, const ProjectionParams& params) {
  const float h = params.h;
  if (!(h > 0) || !std::isfinite(h)) throw Error("h must be a positive number (got " + std::to_string(h) + ")");
  const std::uint64_t n = cloud.size();
  SupportWidths out;
  out.least = out.median = out.largest = h;
  out.h.assign(std::size_t(n), h);
  if (params.support == Support::global || n < 2) return out;
  const UnitFrame frame = unit_frame_of_box(glm::dvec3(cloud.bounds().lo), glm::dvec3(cloud.bounds().hi));
  const std::size_t stride = noise_query_stride(std::size_t(n));
  const std::size_t queries = std::size_t((n + stride - 1) / stride);

  // The first pass: each sample's spacing, and σ at the noise queries.
  std::vector<float> spacing(std::size_t(n), 0.0f), least(std::size_t(n), 0.0f);
  std::vector<vec3> at(queries);
  std::vector<float> measured(queries);
  std::uint64_t row_like = 0;
  {
    Progress progress("support widths (spacing)", std::int64_t(n));
    for_each_tile(cloud, frame, progress, [&](const UnitTile& tile) {
      SupportSteps steps(tile.set(n, frame.scale));
      // query_spacing looks farther until it finds k neighbours: none here yet.
      if (tile.unit.size() <= std::size_t(steps.k())) return false;
      steps.measure_spacing(false);
      const std::size_t own = tile.points.own;
      for (std::size_t i = 0; i < own; ++i)
        if (!steps.complete(i)) return false;  // before the noise's grid: this halo is too narrow anyway
      const UniformGrid grid(tile.unit, 1e-7f, std::max<long long>(4096, (long long)tile.unit.size()));
      const GridView view = grid.view();
      const float cell = 1.0f / view.inv_cell;
      std::vector<char> held(own, 1);
      cpu::parallel_for(std::int64_t(own), [&](std::int64_t s) {
        const auto i = std::size_t(s);
        const std::uint64_t id = tile.points.index[i];
        if (id % stride == 0) {
          const QuerySpacing q = query_spacing(view, cell, tile.unit[i], steps.k(), true);
          at[std::size_t(id / stride)] = tile.unit[i];
          measured[std::size_t(id / stride)] = measured_noise(q);
          held[i] = tile.margin.empty() || q.reach <= tile.margin[i];
        }
      });
      if (!std::all_of(held.begin(), held.end(), [](char c) { return c != 0; })) return false;
      for (std::size_t i = 0; i < own; ++i) {
        spacing[std::size_t(tile.points.index[i])] = steps.spacing()[i];
        least[std::size_t(tile.points.index[i])] = steps.least()[i];
        row_like += steps.row_like(i);
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
  const RegionalNoise noise(std::move(at), std::move(measured));

  // The second pass: which samples widen, and each width, from the first's spacings.
  Progress progress("support widths", std::int64_t(n));
  for_each_tile(cloud, frame, progress, [&](const UnitTile& tile) {
    SupportSteps steps(tile.set(n, frame.scale));
    std::vector<float> set_spacing(tile.unit.size()), set_least(tile.unit.size());
    for (std::size_t i = 0; i < tile.unit.size(); ++i) {
      set_spacing[i] = spacing[std::size_t(tile.points.index[i])];
      set_least[i] = least[std::size_t(tile.points.index[i])];
    }
    steps.use_spacing(std::move(set_spacing), std::move(set_least));
    steps.find_wide(median_d);
    const std::size_t own = tile.points.own;
    for (std::size_t i = 0; i < own; ++i)
      if (!steps.complete(i)) return false;
    cpu::parallel_for(std::int64_t(own), [&](std::int64_t s) {
      const auto i = std::size_t(s);
      out.h[std::size_t(tile.points.index[i])] = adaptive_width(h, widest, steps.wide(i), steps.spacing()[i], median_d,
                                                                noise.about(tile.unit[i]), frame.scale);
    });
    return true;
  });
  out.least = *std::min_element(out.h.begin(), out.h.end());
  out.largest = *std::max_element(out.h.begin(), out.h.end());
  out.median = median_of(out.h);
  return out;
}

}  // namespace pss
