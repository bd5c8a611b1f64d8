#include "pss/tiles/spacing.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "pss/backend/cpu/parallel_for.hpp"
#include "pss/core/error.hpp"
#include "pss/core/progress.hpp"
#include "pss/points/noise.hpp"
#include "pss/points/unit_frame.hpp"
#include "pss/spatial/uniform_grid.hpp"
#include "halo_guess.hpp"

namespace pss {

SpacingEstimate estimate_spacing(const TiledCloud& cloud, int k, std::size_t max_samples) {
  const std::uint64_t n = cloud.size();
  if (n < 2) throw Error("cannot estimate the sample spacing of fewer than two points");
  k = int(std::min<std::uint64_t>(std::uint64_t(k), n - 1));
  // The in-core frame: the box of the same floats.
  const UnitFrame frame = cloud.unit_frame();
  const double scale = frame.scale;

  const std::size_t stride = spacing_stride(std::size_t(n), max_samples);
  const std::size_t queries = std::size_t((n + stride - 1) / stride);
  std::vector<QuerySpacing> results(queries);
  const std::size_t noise_stride = noise_query_stride(queries);
  Progress progress("spacing", std::int64_t(n));
  HaloGuess guess;
  for (const int t : cloud.tiles_with_points()) {
    const Aabb box = cloud.tile_box(t);
    const float width = box.hi.x - box.lo.x;
    // A query's k nearest lie within its k-th distance of it, and the points its noise is
    // fitted to within its reach, so within that of the tile's box: a halo that wide holds
    // them all.
    for (float halo = guess.first(width);; halo *= 2) {
      const TilePoints tile = cloud.load(t, halo);
      if (tile.positions.size() <= std::size_t(k)) continue;  // no query's k nearest here yet
      std::vector<vec3> unit(tile.positions.size());
      for (std::size_t i = 0; i < unit.size(); ++i) unit[i] = frame.to_unit(tile.positions[i]);
      const UniformGrid grid(unit, 1e-7f, std::max<long long>(4096, (long long)unit.size()));
      const GridView view = grid.view();
      const float cell = 1.0f / view.inv_cell;
      const NoiseGrids noise(unit, view);
      std::vector<std::size_t> mine;
      for (std::size_t i = 0; i < tile.own; ++i)
        if (tile.index[i] % stride == 0) mine.push_back(i);
      std::vector<char> held(mine.size(), 1);
      cpu::parallel_for(std::int64_t(mine.size()), [&](std::int64_t m) {
        const std::size_t i = mine[std::size_t(m)];
        const auto query = std::size_t(tile.index[i] / stride);
        const QuerySpacing s = query_spacing(view, cell, unit[i], k, query % noise_stride == 0 ? &noise.views() : nullptr);
        results[query] = s;
        held[std::size_t(m)] = s.reach * scale * (1 + 1e-6) <= double(halo) || tile.positions.size() == n;
      });
      if (std::all_of(held.begin(), held.end(), [](char h) { return h != 0; })) {
        guess.held(halo, width);
        break;
      }
    }
    progress.advance(std::int64_t(cloud.tile_size(t)));
  }
  return spacing_of(results, k, scale);
}

}  // namespace pss
