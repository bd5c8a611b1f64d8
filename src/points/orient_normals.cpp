#include "pss/points/orient_normals.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <vector>

#include "pss/core/error.hpp"
#include "pss/core/indexed_min_heap.hpp"
#include "pss/core/memory.hpp"
#include "pss/core/progress.hpp"
#include "pss/points/facing_vote.hpp"
#include "pss/points/visibility.hpp"
#include "pss/spatial/support_grid.hpp"

namespace pss {

namespace {

// Orients `sorted`, the normals of the grid's samples in its sorted order, each part from its
// highest point's +z; rank(k) is sorted point k's place in the cloud. Returns each sorted
// point's part and each part's root, in sorted indices; `tree`, where given, gets the tree's
// edges (visibility.hpp turns its signs where the rays see otherwise).
template <class Rank>
OrientedParts orient_sorted(const SupportGrid& grid, std::span<vec3> sorted, Rank rank, Progress* progress,
                            SpanningTree* tree = nullptr) {
  const SupportGridView view = grid.view();
  // The tree grows in the grid's order, where a point's neighbours lie near it in memory.
  // Ties go by the cloud's order, so the tree is the one that order gives.
  const std::span<const vec3> at = grid.sorted_points();
  const std::size_t n = at.size();

  std::vector<int> by_height(n);
  std::iota(by_height.begin(), by_height.end(), 0);
  std::sort(by_height.begin(), by_height.end(),
            [&](int a, int b) { return at[a].z > at[b].z || (at[a].z == at[b].z && rank(a) < rank(b)); });

  // Per point: whether the tree holds it, and whether its cheapest edge yet from the tree
  // reaches it from a normal facing the other way. That end is in the tree, so its normal is
  // final: one bit instead of the end's index.
  constexpr unsigned char kDone = 1, kAgainst = 2;
  std::vector<unsigned char> state(n, 0);
  std::vector<float> cheapest(n, kInfinity);  // the cheapest edge yet from the tree to each point
  // The points the tree may reach next, by their cheapest edge's cost, then input index.
  IndexedMinHeap frontier(n, [&](int a, int b) {
    const float ca = cheapest[std::size_t(a)], cb = cheapest[std::size_t(b)];
    return ca < cb || (ca == cb && rank(a) < rank(b));
  });
  // One thread: advancing once per 4096 points oriented keeps the atomic out of the inner loop.
  std::size_t oriented = 0;
  OrientedParts parts;
  parts.of_point.assign(n, -1);
  if (tree) {
    tree->parent.assign(n, -1);
    tree->order.clear();
    tree->order.reserve(n);
  }
  for (int seed : by_height) {
    if (state[std::size_t(seed)] & kDone) continue;
    parts.root.push_back(seed);
    if (sorted[seed].z < 0) sorted[seed] = -sorted[seed];
    cheapest[std::size_t(seed)] = 0;
    frontier.lowered(seed);
    while (!frontier.empty()) {
      const int i = frontier.pop();
      // Prim's order: the cheapest edge to i when it is reached is its tree edge.
      if (state[std::size_t(i)] & kAgainst) sorted[i] = -sorted[i];
      state[std::size_t(i)] = kDone;
      parts.of_point[std::size_t(i)] = int(parts.root.size()) - 1;
      if (tree) tree->order.push_back(i);
      if (++oriented % 4096 == 0 && progress) progress->advance(4096);
      view.for_each_covering(at[i], [&](vec3 q, float d2, int j) {
        if (state[std::size_t(j)] & kDone) return;
        // Along the surface, not across it: a neighbour stacked above or below (the other
        // face of a thin part, whose normal is as parallel) is reached last.
        const float across = d2 > 0 ? std::abs(glm::dot(q - at[i], sorted[i])) / std::sqrt(d2) : 0.0f;
        const float facing = glm::dot(sorted[i], sorted[j]);
        const float cost = 1.0f - std::abs(facing) + across;
        if (!(cost < cheapest[std::size_t(j)])) return;
        cheapest[std::size_t(j)] = cost;
        state[std::size_t(j)] = facing < 0 ? kAgainst : 0;
        if (tree) tree->parent[std::size_t(j)] = i;
        frontier.lowered(j);
      });
    }
  }
  return parts;
}

// Turns each part whose converged points vote that it faces inward (facing_vote.hpp); the
// supports ρ are the grid's κ·h_i (its widths where κ = 1, as the tiles' grids are built).
template <class Status>
void face_as_voted(const SupportGrid& grid, std::span<vec3> sorted, const OrientedParts& parts, Status status,
                   std::span<const char> seen) {
  const std::span<const vec3> at = grid.sorted_points();
  const std::span<const float> inv_h2 = grid.inv_h2();
  const float kappa2 = grid.kappa() * grid.kappa();
  std::vector<FacingVote> votes(parts.root.size());
  for (std::size_t k = 0; k < sorted.size(); ++k)
    votes[std::size_t(parts.of_point[k])].add(at[k], sorted[k], inv_h2[k] / kappa2, status(k));
  std::vector<char> turns(votes.size());
  for (std::size_t p = 0; p < votes.size(); ++p) turns[p] = !seen[p] && votes[p].sign() < 0;
  release(votes);
  for (std::size_t k = 0; k < sorted.size(); ++k)
    if (turns[std::size_t(parts.of_point[k])]) sorted[k] = -sorted[k];
}

// The tree's signs turned where the rays see otherwise (visibility.hpp); per part, whether
// they decided. `progress`, where given, takes a step more a sample for the rays.
std::vector<char> face_as_seen(const SupportGrid& grid, std::span<vec3> sorted, const OrientedParts& parts,
                               const SpanningTree& tree, Progress* progress = nullptr) {
  const std::span<const float> inv_h2 = grid.inv_h2();
  std::vector<float> radius(inv_h2.size());
  for (std::size_t k = 0; k < radius.size(); ++k) radius[k] = visibility_radius(grid.kappa() / std::sqrt(inv_h2[k]));
  if (progress) progress->add_total(std::int64_t(sorted.size()));
  return face_as_seen(grid.sorted_points(), sorted, radius, parts.of_point, parts.root.size(), tree, progress);
}

std::vector<vec3> sorted_normals(const SupportGrid& grid, std::span<const vec3> normals) {
  const std::span<const int> original = grid.original_index();
  std::vector<vec3> sorted(original.size());
  for (std::size_t k = 0; k < sorted.size(); ++k) sorted[k] = normals[std::size_t(original[k])];
  return sorted;
}

void check_one_normal_per_point(std::size_t points, std::size_t normals) {
  if (normals != points) throw Error("orient normals: one normal per point is needed");
}

void check_one_status_per_point(std::size_t points, std::size_t status) {
  if (status != points) throw Error("orient normals: one projection status per point is needed");
}

}  // namespace

void orient_normals_consistently(std::span<const vec3> points, std::span<vec3> normals, std::span<const float> radius,
                                 std::span<const ProjectionStatus> status) {
  check_one_normal_per_point(points.size(), normals.size());
  check_one_status_per_point(points.size(), status.size());
  const SupportGrid grid(points, radius, 1.0f);
  std::vector<vec3> sorted = sorted_normals(grid, normals);
  const std::span<const int> original = grid.original_index();
  Progress progress("orient normals", std::int64_t(points.size()));
  SpanningTree tree;
  const OrientedParts parts =
      orient_sorted(grid, sorted, [&](int k) { return original[std::size_t(k)]; }, &progress, &tree);
  const std::vector<char> seen = face_as_seen(grid, sorted, parts, tree, &progress);
  face_as_voted(grid, sorted, parts, [&](std::size_t k) { return status[std::size_t(original[k])]; }, seen);
  for (std::size_t k = 0; k < sorted.size(); ++k) normals[std::size_t(original[k])] = sorted[k];
}

void orient_grid_normals(const SupportGrid& grid, std::span<vec3> sorted_normals,
                         std::span<const ProjectionStatus> sorted_status) {
  check_one_normal_per_point(grid.sorted_points().size(), sorted_normals.size());
  check_one_status_per_point(grid.sorted_points().size(), sorted_status.size());
  const std::span<const int> original = grid.original_index();
  Progress progress("orient normals", std::int64_t(original.size()));
  SpanningTree tree;
  const OrientedParts parts =
      orient_sorted(grid, sorted_normals, [&](int k) { return original[std::size_t(k)]; }, &progress, &tree);
  const std::vector<char> seen = face_as_seen(grid, sorted_normals, parts, tree, &progress);
  face_as_voted(grid, sorted_normals, parts, [&](std::size_t k) { return sorted_status[k]; }, seen);
}

std::size_t face_file_normals_as_seen(const SupportGrid& grid, std::span<vec3> file) {
  if (file.size() != grid.sorted_points().size()) throw Error("orient normals: one normal per point is needed");
  const std::span<const int> original = grid.original_index();
  std::vector<vec3> along(file.begin(), file.end());
  SpanningTree tree;
  const OrientedParts parts =
      orient_sorted(grid, std::span<vec3>(along), [&](int k) { return original[std::size_t(k)]; }, nullptr, &tree);
  const std::vector<char> decided = face_as_seen(grid, along, parts, tree);
  std::vector<std::size_t> size(parts.root.size(), 0), against(parts.root.size(), 0);
  for (std::size_t k = 0; k < file.size(); ++k) {
    const auto p = std::size_t(parts.of_point[k]);
    size[p] += 1;
    against[p] += glm::dot(along[k], file[k]) < 0;
  }
  std::vector<char> mends(parts.root.size(), 0);
  for (std::size_t p = 0; p < mends.size(); ++p) {
    const double share = double(against[p]) / double(std::max<std::size_t>(size[p], 1));
    mends[p] = decided[p] && share >= kFileAgainstShare && share <= 1 - kFileAgainstShare;
  }
  std::size_t turned = 0;
  for (std::size_t k = 0; k < file.size(); ++k)
    if (mends[std::size_t(parts.of_point[k])] && glm::dot(along[k], file[k]) < 0) {
      file[k] = -file[k];
      ++turned;
    }
  return turned;
}

OrientedParts orient_normals_in_parts(std::span<const vec3> points, std::span<vec3> normals,
                                      std::span<const float> radius, std::span<const std::uint64_t> id,
                                      SpanningTree* tree) {
  check_one_normal_per_point(points.size(), normals.size());
  if (id.size() != points.size()) throw Error("orient normals: one index per point is needed");
  const SupportGrid grid(points, radius, 1.0f);
  std::vector<vec3> sorted = sorted_normals(grid, normals);
  const std::span<const int> original = grid.original_index();
  const OrientedParts sorted_parts =
      orient_sorted(grid, sorted, [&](int k) { return id[std::size_t(original[std::size_t(k)])]; }, nullptr, tree);
  if (tree) {  // from the grid's order to the points'
    std::vector<int> parent(points.size(), -1);
    for (std::size_t k = 0; k < parent.size(); ++k)
      if (tree->parent[k] >= 0) parent[std::size_t(original[k])] = original[std::size_t(tree->parent[k])];
    tree->parent = std::move(parent);
    for (int& k : tree->order) k = original[std::size_t(k)];
  }
  OrientedParts parts;
  parts.of_point.resize(points.size());
  for (std::size_t k = 0; k < sorted.size(); ++k) {
    normals[std::size_t(original[k])] = sorted[k];
    parts.of_point[std::size_t(original[k])] = sorted_parts.of_point[k];
  }
  for (const int root : sorted_parts.root) parts.root.push_back(original[std::size_t(root)]);
  return parts;
}

void orient_normals_consistently(std::vector<vec3>& points, std::vector<vec3>& normals, std::vector<float>&& radius,
                                 std::span<const ProjectionStatus> status) {
  check_one_normal_per_point(points.size(), normals.size());
  check_one_status_per_point(points.size(), status.size());
  const SupportGrid grid(points, radius, 1.0f);
  // Each array freed as soon as it is copied: the grid's copy of the points and the sorted
  // normals are never held beside the lent ones.
  release(radius);
  release(points);
  std::vector<vec3> sorted = sorted_normals(grid, normals);
  release(normals);
  const std::span<const int> original = grid.original_index();
  {
    Progress progress("orient normals", std::int64_t(original.size()));
    SpanningTree tree;
    const OrientedParts parts =
        orient_sorted(grid, sorted, [&](int k) { return original[std::size_t(k)]; }, &progress, &tree);
    const std::vector<char> seen = face_as_seen(grid, sorted, parts, tree, &progress);
    face_as_voted(grid, sorted, parts, [&](std::size_t k) { return status[std::size_t(original[k])]; }, seen);
  }
  const std::size_t n = original.size();
  normals.resize(n);
  for (std::size_t k = 0; k < n; ++k) normals[std::size_t(original[k])] = sorted[k];
  release(sorted);
  points.resize(n);
  for (std::size_t k = 0; k < n; ++k) points[std::size_t(original[k])] = grid.sorted_points()[k];
}

}  // namespace pss
