// The seams' turn tile by tile: a tile's part of each of its steps (tile_works.hpp).
#include "pss/backend/cpu/parallel_for.hpp"
#include "pss/core/connected_components.hpp"
#include "pss/core/error.hpp"
#include "pss/core/gather.hpp"
#include "tile_arrays.hpp"
#include "tile_works.hpp"

namespace pss {

namespace {

void put_joins(ByteWriter& result, const SupportGrid& grid, std::span<const int> own) {
  const std::span<const int> original = grid.original_index();
  ConnectedComponents joined(original.size());
  cpu::parallel_for(std::int64_t(own.size()), [&](std::int64_t m) {
    thread_local std::vector<int> with;
    const int i = own[std::size_t(m)];
    patch_joins(grid.view(), grid.normals(), i, with);
    for (const int j : with) joined.join(i, j);
  });
  std::vector<int> point, root;  // in the set; a root is joined to itself, and needs no pair
  for (std::size_t k = 0; k < original.size(); ++k) {
    const int r = joined.find(int(k));
    if (r == int(k)) continue;
    point.push_back(original[k]);
    root.push_back(original[std::size_t(r)]);
  }
  result.put_array<int>(point);
  result.put_array<int>(root);
}

void put_evidence(ByteWriter& result, const SupportGrid& grid, std::span<const int> own,
                  std::span<const std::uint32_t> patch_of_point) {
  const std::vector<std::uint32_t> patch = gathered<std::uint32_t>(patch_of_point, grid.original_index());
  EvidenceTallies tallies;
  cpu::parallel_for(std::int64_t(own.size()), [&](std::int64_t m) {
    tallies.add(grid.view(), grid.normals(), patch, own[std::size_t(m)]);
  });
  const PatchEvidence between = tallies.sum();
  std::vector<std::uint64_t> key;
  std::vector<std::int64_t> flip, keep;
  for (const auto& [k, e] : between) {
    key.push_back(k);
    flip.push_back(e.flip);
    keep.push_back(e.keep);
  }
  result.put_array<std::uint64_t>(key);
  result.put_array<std::int64_t>(flip);
  result.put_array<std::int64_t>(keep);
}

void put_says(ByteWriter& result, const SupportGrid& grid, std::span<const int> own,
              std::span<const char> settled_point) {
  const std::vector<char> settled = gathered<char>(settled_point, grid.original_index());
  std::vector<int> straggler;
  for (const int i : own)
    if (!settled[std::size_t(i)]) straggler.push_back(i);
  std::vector<double> say(straggler.size());
  cpu::parallel_for(std::int64_t(straggler.size()), [&](std::int64_t m) {
    say[std::size_t(m)] = straggler_say(grid.view(), grid.normals(), settled, straggler[std::size_t(m)]);
  });
  for (int& i : straggler) i = grid.original_index()[std::size_t(i)];
  result.put_array<int>(straggler);
  result.put_array<double>(say);
}

}  // namespace

std::vector<std::byte> seam_turn_request(const UnitTile& tile, SeamStep step, std::span<const std::uint32_t> patch,
                                         std::span<const char> settled) {
  ByteWriter out;
  put_tile(out, tile);
  out.put(step);
  out.put_array(patch);
  out.put_array(settled);
  return out.take();
}

std::vector<std::byte> work_seam_turn(std::span<const std::byte> request) {
  ByteReader in(request);
  const TileArrays t = get_tile(in);
  const auto step = in.get<SeamStep>();
  const std::vector<std::uint32_t> patch = in.get_array<std::uint32_t>();
  const std::vector<char> settled = in.get_array<char>();
  const std::size_t m = t.unit.size();
  const bool whole = t.normals.size() == m && (step != SeamStep::evidence || patch.size() == m) &&
                     (step != SeamStep::stragglers || settled.size() == m) && std::uint8_t(step) <= 2;
  if (!whole) throw Error("a tile's work does not hold together: the seams' turn needs the samples' normals");
  const SupportGrid grid = grid_of_tile(t);
  const std::vector<int> own = own_sorted_samples(grid, t.own);
  ByteWriter result;
  if (step == SeamStep::joins) put_joins(result, grid, own);
  if (step == SeamStep::evidence) put_evidence(result, grid, own, patch);
  if (step == SeamStep::stragglers) put_says(result, grid, own, settled);
  return result.take();
}

TileSeamTurn seam_turn_result(std::span<const std::byte> result, SeamStep step) {
  ByteReader in(result);
  TileSeamTurn done;
  bool whole = true;
  if (step == SeamStep::joins) {
    done.joined = in.get_array<int>();
    done.root = in.get_array<int>();
    whole = done.root.size() == done.joined.size();
  } else if (step == SeamStep::evidence) {
    const std::vector<std::uint64_t> key = in.get_array<std::uint64_t>();
    const std::vector<std::int64_t> flip = in.get_array<std::int64_t>(), keep = in.get_array<std::int64_t>();
    whole = flip.size() == key.size() && keep.size() == key.size();
    for (std::size_t k = 0; whole && k < key.size(); ++k) done.evidence[key[k]] = {flip[k], keep[k]};
  } else {
    done.straggler = in.get_array<int>();
    done.say = in.get_array<double>();
    whole = done.say.size() == done.straggler.size();
  }
  if (!whole) throw Error("a tile's seams' turn does not hold together");
  return done;
}

}  // namespace pss
