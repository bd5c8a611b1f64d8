#include "pss/points/turn_flipped_normals.hpp"

#include <algorithm>
#include <cstdint>
#include <utility>
#include <vector>

#include "pss/backend/cpu/parallel_for.hpp"
#include "pss/core/connected_components.hpp"
#include "pss/points/seam_turn.hpp"

namespace pss {

std::size_t turn_flipped_normals(const SupportGrid& grid, std::span<vec3> normals) {
  const std::span<const vec3> points = grid.sorted_points();
  const std::span<const float> inv_h2 = grid.inv_h2();
  const std::span<const int> original = grid.original_index();
  const SupportGridView view = grid.view();
  const std::size_t n = points.size();
  // The patches, numbered 0, 1, ... in the cloud's order of their least samples (so that tiles
  // number them alike): what follows is sized by their number (at most n/kFewestPerPatch),
  // not by the samples' (issue 28).
  std::vector<std::uint32_t> patch(n);
  std::size_t patches = 0;
  {
    ConnectedComponents joined(n);
    cpu::parallel_for(std::int64_t(n), [&](std::int64_t i) {
      thread_local std::vector<int> with;
      patch_joins(view, normals, int(i), with);
      for (const int j : with) joined.join(int(i), j);
    });
    std::vector<int> least(n);  // per root, its patch's least sample in the cloud
    for (std::size_t i = 0; i < n; ++i) least[i] = original[i];
    for (std::size_t i = 0; i < n; ++i) {
      const auto root = std::size_t(joined.find(int(i)));
      patch[i] = std::uint32_t(root);
      least[root] = std::min(least[root], original[i]);
    }
    std::vector<std::pair<int, std::uint32_t>> roots;  // (least sample, root)
    for (std::size_t i = 0; i < n; ++i)
      if (patch[i] == i) roots.push_back({least[i], std::uint32_t(i)});
    std::sort(roots.begin(), roots.end());
    for (std::size_t k = 0; k < roots.size(); ++k) least[roots[k].second] = int(k);
    for (std::size_t i = 0; i < n; ++i) patch[i] = std::uint32_t(least[patch[i]]);
    patches = roots.size();
  }
  // Normals so scattered that they form no patches of a few samples weigh nothing against
  // each other (and would make the tallies below as large as the neighbourhoods).
  if (patches > n / kFewestPerPatch) return 0;
  std::vector<std::uint64_t> patch_size(patches, 0);
  for (const std::uint32_t p : patch) ++patch_size[p];
  // The evidence between patches, each pair seen from both its samples.
  PatchGroups groups(patch_size, [&] {
    EvidenceTallies tallies;
    cpu::parallel_for(std::int64_t(n), [&](std::int64_t i) { tallies.add(view, normals, patch, int(i)); });
    return tallies.sum();
  }());
  std::vector<char> turned_by_groups(patches, 0);
  if (groups.linked()) {
    for (std::size_t i = 0; i < n; ++i) groups.add(patch[i], points[i], normals[i], inv_h2[i]);
    turned_by_groups = groups.turns();
    for (std::size_t i = 0; i < n; ++i)
      if (turned_by_groups[patch[i]]) normals[i] = -normals[i];
  }
  // Patches too small for the evidence between patches face as the surfaces they lie on.
  std::vector<char> settled(n);
  for (std::size_t i = 0; i < n; ++i) settled[i] = patch_size[patch[i]] >= kFewestPerPatch;
  StragglerSays says(patches);
  for (std::size_t i = 0; i < n; ++i)
    if (!settled[i]) says.add(patch[i], straggler_say(view, normals, settled, int(i)));
  const std::vector<char> turn = says.turns();
  std::size_t turned = 0;  // the stragglers' turn after the groups', counted once where it turns a normal back
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint32_t p = patch[i];
    if (turn[p]) normals[i] = -normals[i];
    turned += (turn[p] != 0) != (turned_by_groups[p] != 0);
  }
  return turned;
}

}  // namespace pss
