#include "pss/points/turn_flipped_normals.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <unordered_map>
#include <vector>

#include <omp.h>

#include "pss/backend/cpu/parallel_for.hpp"
#include "pss/core/connected_components.hpp"
#include "pss/fit/weights.hpp"
#include "pss/points/facing_vote.hpp"

namespace pss {

namespace {

// Agreeing and opposed normals: 45° of slack either way, far from a crease's 90°.
constexpr float kAgree = 0.7f;
// |offset along the normals| / distance: side by side below, stacked above.
constexpr float kSideBySide = 0.3f;
// |mean unit direction| of a sample's opposed neighbours above which they lie to one side.
constexpr float kOneSided = 0.4f;
// |facing| (Pair) above which a pair off each other's tangent planes tells a side.
constexpr float kFacing = 0.05f;
// Patches are weighed against each other only where they average this many samples or more.
constexpr std::size_t kFewestPerPatch = 8;

// A union-find of the patches, each member with its parity against its root: linking a and b
// as flipped against each other (odd) or not. A link that contradicts the parities already
// set is refused. Union by size and path compression (the parities carried along), so that
// many links in any order stay near linear.
struct ParityUnionFind {
  explicit ParityUnionFind(std::size_t n) : parent(n), size(n, 1), parity(n, 0) {
    std::iota(parent.begin(), parent.end(), 0);
  }
  int find(int i, int& p) {
    int root = i, total = 0;
    while (parent[std::size_t(root)] != root) {
      total ^= parity[std::size_t(root)];
      root = parent[std::size_t(root)];
    }
    for (int at = total; parent[std::size_t(i)] != i;) {  // each node on the way now points at the root
      const int next = parent[std::size_t(i)], own = parity[std::size_t(i)];
      parent[std::size_t(i)] = root;
      parity[std::size_t(i)] = char(at);
      at ^= own;
      i = next;
    }
    p = total;
    return root;
  }
  void link(int a, int b, int odd) {
    int pa, pb;
    int ra = find(a, pa), rb = find(b, pb);
    if (ra == rb) return;
    if (size[std::size_t(ra)] < size[std::size_t(rb)]) std::swap(ra, rb);
    parent[std::size_t(rb)] = ra;
    parity[std::size_t(rb)] = char(pa ^ pb ^ odd);
    size[std::size_t(ra)] += size[std::size_t(rb)];
  }
  std::vector<int> parent, size;
  std::vector<char> parity;
};

// Two neighbours: the squared distance in ρ_i, n_i·n_j, the larger squared offset along a
// normal over the squared distance, and −(e·n_i)(e·n_j)/|e|² for e = p_j − p_i: positive
// where the two agree on which side of each other they lie (each behind the other's face,
// or each before it), negative where one faces toward the other and the other away.
struct Pair {
  int i, j;
  float in_rho2, agreement, offset2, facing;
};

// For turning one patch against another, and for keeping them as they are.
struct Evidence {
  std::int64_t flip = 0, keep = 0;
};

// Patches a and b, flipped against each other (odd) or not, by this much more evidence.
struct Link {
  std::int64_t strength;
  int a, b, odd;
};

// Whether a group, its odd side turned, encloses a volume, where its vote on heights has no
// say (facing_vote.hpp: the dragon's true normals give 0.28 of their magnitudes there, near
// the quarter it asks): by the divergence theorem in all three axes, Σ (p − c)·n ρ² = 3V about
// any c, so a closed surface (|Σ n ρ²| under a tenth of Σ ρ²: the bunny, its base open, 0.04)
// faces outward where the sum about the centroid c is positive (the patches of a group face
// consistently, whichever side they keep). Open surfaces (the ground and its roofs: |Σ n ρ²|
// near Σ ρ²) have no say.
class Enclosure {
 public:
  void add(vec3 p, vec3 n, double area) {
    const glm::dvec3 at(p), normal(n);
    area_ += area;
    normal_ += area * normal;
    position_ += area * at;
    outward_ += area * glm::dot(at, normal);
  }
  int sign() const {
    if (!(area_ > 0) || !(glm::length(normal_) <= kClosed * area_)) return 0;
    const glm::dvec3 centre = position_ / area_;
    const double volume = outward_ - glm::dot(centre, normal_);
    return volume > 0 ? 1 : (volume < 0 ? -1 : 0);
  }

 private:
  static constexpr double kClosed = 0.1;
  double area_ = 0, outward_ = 0;
  glm::dvec3 normal_{0.0}, position_{0.0};
};

// Which patches turn after the groups' turn (`normals` as it left them): those too small for
// the evidence between patches (fewer than kFewestPerPatch samples) face as the surfaces they
// lie on: the normals of the larger patches'
// samples in whose tangent planes they lie, weighted as the fits weigh them. Such is a
// sample on a crease whose normal lies between its faces' (a CAD file's): it agrees with no
// neighbour within 45°, and its pairs with them are neither side by side nor plainly one
// behind the other's face, so they weigh nothing or mislead (cube.pwn: six left inward on
// its slots' edges cut five holes in its mesh). A thin part's other face does not pass
// through the sample, and so has no say.
std::vector<char> stragglers_to_turn(const SupportGridView& view, std::span<const vec3> points,
                                     std::span<const float> inv_h2, std::span<const vec3> normals,
                                     std::span<const int> patch, std::span<const std::size_t> patch_size) {
  const std::size_t patches = patch_size.size();
  const auto settled = [&](int p) { return patch_size[std::size_t(p)] >= kFewestPerPatch; };
  std::vector<double> say(patches, 0.0);  // per straggling patch: + keep, − turn
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (settled(patch[i])) continue;
    vec3 around(0.0f);
    view.for_each_near(points[i], [&](vec3 q, int j) {
      const vec3 e = q - points[i];
      const float d2 = glm::dot(e, e);
      if (!view.covers(int(i), d2) || d2 == 0 || !settled(patch[std::size_t(j)])) return;
      const vec3 n_j = normals[std::size_t(j)];
      const float z = glm::dot(e, n_j);
      if (z * z < kSideBySide * kSideBySide * d2) around += gaussian_weight(d2, inv_h2[i]) * n_j;
    });
    say[std::size_t(patch[i])] += double(glm::dot(around, normals[i]));
  }
  std::vector<char> turn(patches);
  for (std::size_t p = 0; p < patches; ++p) turn[p] = say[p] < 0;
  return turn;
}

}  // namespace

std::size_t turn_flipped_normals(const SupportGrid& grid, std::span<vec3> normals) {
  const std::span<const vec3> points = grid.sorted_points();
  const std::span<const float> inv_h2 = grid.inv_h2();
  const SupportGridView view = grid.view();
  const std::size_t n = points.size();
  // f(pair) for sample i's neighbours j ≠ i within its support ρ_i.
  const auto for_each_neighbour = [&](int i, auto&& f) {
    view.for_each_near(points[std::size_t(i)], [&](vec3 q, int j) {
      if (j == i) return;
      const vec3 e = q - points[std::size_t(i)];
      const float d2 = glm::dot(e, e);
      if (!view.covers(i, d2) || d2 == 0) return;
      const float zi = glm::dot(e, normals[std::size_t(i)]), zj = glm::dot(e, normals[std::size_t(j)]);
      Pair pair;
      pair.i = i;
      pair.j = j;
      pair.in_rho2 = d2 * inv_h2[std::size_t(i)] / view.kappa2;
      pair.agreement = glm::dot(normals[std::size_t(i)], normals[std::size_t(j)]);
      pair.offset2 = std::max(zi * zi, zj * zj) / d2;
      pair.facing = -zi * zj / d2;
      f(pair, e);
    });
  };
  // The patches, numbered 0, 1, ... in the order of their least samples: what follows is sized
  // by their number (at most n/kFewestPerPatch), not by the samples' (issue 28).
  std::vector<int> patch(n);
  {
    ConnectedComponents joined(n);
    cpu::parallel_for(std::int64_t(n), [&](std::int64_t i) {
      for_each_neighbour(int(i), [&](const Pair& p, vec3) {
        if (p.j > p.i && p.in_rho2 <= 0.25f && p.agreement > kAgree && p.offset2 < kSideBySide * kSideBySide)
          joined.join(p.i, p.j);
      });
    });
    cpu::parallel_for(std::int64_t(n), [&](std::int64_t i) { patch[std::size_t(i)] = joined.find(int(i)); });
  }
  // Each patch's least sample (its root, patch[i] == i) takes the number −1 − k, for the k-th
  // patch; then every sample its root's; then all are made k.
  int patches = 0;
  for (std::size_t i = 0; i < n; ++i)
    if (patch[i] == int(i)) patch[i] = -1 - patches++;
  for (std::size_t i = 0; i < n; ++i)
    if (patch[i] >= 0) patch[i] = patch[std::size_t(patch[i])];
  for (int& p : patch) p = -1 - p;
  // Normals so scattered that they form no patches of a few samples weigh nothing against
  // each other (and would make the tallies below as large as the neighbourhoods).
  if (std::size_t(patches) > n / kFewestPerPatch) return 0;
  std::vector<std::size_t> patch_size(std::size_t(patches), 0);
  for (const int p : patch) ++patch_size[std::size_t(p)];
  // The evidence between patches, each pair seen from both its samples (each thread its own
  // tally, summed after: sums, so the same for any thread count). From sample i: where its
  // opposed and agreeing neighbours lie in its tangent plane, the means of their unit
  // directions. Along a seam the opposed ones lie to one side, and the agreeing ones all
  // around or to the other; on a thin part the other face's samples surround i (their mean is
  // short), or, at its rim, lie on the same side as i's own.
  std::vector<std::unordered_map<std::uint64_t, Evidence>> tallies(std::size_t(std::max(1, omp_get_max_threads())));
  cpu::parallel_for(std::int64_t(n), [&](std::int64_t i) {
    thread_local std::vector<Pair> around;
    around.clear();
    const vec3 n_i = normals[std::size_t(i)];
    vec3 toward_opposed(0.0f), toward_agreeing(0.0f);
    int opposed = 0, agreeing = 0;
    for_each_neighbour(int(i), [&](const Pair& p, vec3 e) {
      around.push_back(p);
      if (!(p.agreement < -kAgree) && !(p.agreement > kAgree)) return;
      const vec3 tangential = e - glm::dot(e, n_i) * n_i;
      const float length = glm::length(tangential);
      if (!(length > 0)) return;
      (p.agreement > 0 ? toward_agreeing : toward_opposed) += tangential / length;
      (p.agreement > 0 ? agreeing : opposed) += 1;
    });
    const float length = glm::length(toward_opposed);
    const bool one_sided = length > kOneSided * float(opposed) &&
                           glm::dot(toward_opposed, toward_agreeing) < kOneSided * length * float(agreeing);
    auto& tally = tallies[std::size_t(omp_get_thread_num())];
    for (const Pair& p : around) {
      const int a = patch[std::size_t(p.i)], b = patch[std::size_t(p.j)];
      if (a == b) continue;
      int flip = 0, keep = 0;
      if (p.offset2 < kSideBySide * kSideBySide) {
        // In each other's tangent plane: a seam where the normals oppose and lie to one side.
        keep = p.agreement > kAgree;
        flip = p.agreement < -kAgree && one_sided;
      } else {
        // Each behind the other's face (a convex crease, a thin part) or each before it (a
        // slot); else one behind and the other before (a crease with one face flipped). Stacked
        // sheets that face alike are that too where they are a thin part's two faces, but they
        // are as often layers, each right (the ground under a canopy or a roof's eaves in an
        // aerial scan: 2,353 of urban.las's good normals were turned), so they tell nothing.
        keep = p.facing > kFacing;
        flip = p.facing < -kFacing && !(p.agreement > kAgree);
      }
      if (flip + keep == 0) continue;
      Evidence& e = tally[(std::uint64_t(std::min(a, b)) << 32) | std::uint64_t(std::max(a, b))];
      e.flip += flip;
      e.keep += keep;
    }
  });
  std::unordered_map<std::uint64_t, Evidence> between;
  for (const auto& tally : tallies)
    for (const auto& [key, e] : tally) {
      between[key].flip += e.flip;
      between[key].keep += e.keep;
    }
  std::vector<Link> links;
  for (const auto& [key, e] : between) {
    const int a = int(key >> 32), b = int(key & 0xffffffffu);
    if (e.flip >= 2 && e.flip > 2 * e.keep) links.push_back({e.flip - e.keep, a, b, 1});
    if (e.keep >= 2 && e.keep > 2 * e.flip) links.push_back({e.keep - e.flip, a, b, 0});
  }
  const auto count = std::size_t(patches);
  // The stragglers' turn after the groups', counted once where it turns a normal back.
  const auto turn_stragglers = [&](std::span<const char> turned_by_groups) {
    const std::vector<char> turn = stragglers_to_turn(view, points, inv_h2, normals, patch, patch_size);
    std::size_t turned = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const auto p = std::size_t(patch[i]);
      if (turn[p]) normals[i] = -normals[i];
      turned += (turn[p] != 0) != (!turned_by_groups.empty() && turned_by_groups[p] != 0);
    }
    return turned;
  };
  if (links.empty()) return turn_stragglers({});
  std::sort(links.begin(), links.end(), [](const Link& x, const Link& y) {
    return x.strength != y.strength ? x.strength > y.strength : (x.a != y.a ? x.a < y.a : x.b < y.b);
  });
  ParityUnionFind flips(count);
  for (const Link& l : links) flips.link(l.a, l.b, l.odd);
  // Each group of linked patches whose sides both hold a patch that weighs (below) turns one
  // side: the one that faces inward as the whole group votes with the other's sign
  // (facing_vote.hpp), or where that vote has no say, as the volume the group encloses says
  // (Enclosure, above), or where neither has (an open surface seen edge-on), the smaller
  // side, if the two sides face opposite ways (their normals' sums): a sheet half flipped.
  // Where they face alike the links do not show a flip, and nothing turns. A file's majority
  // is no guide: cube.pwn's normals, each signed positive along its axis, point inward on the
  // three faces that hold more samples, and the majority turned the whole part inward.
  std::vector<int> group(count), side(count);
  for (int k = 0; k < patches; ++k) group[std::size_t(k)] = flips.find(k, side[std::size_t(k)]);
  std::vector<std::int64_t> odd(count, 0), even(count, 0);
  for (const int p : patch) (side[std::size_t(p)] ? odd : even)[std::size_t(group[std::size_t(p)])] += 1;
  // A group shows a flip only where both its sides hold a patch large enough to weigh; one
  // whose other side is stragglers (fewer than kFewestPerPatch samples a patch) does not: the
  // stragglers' turn settles those. Its vote would turn a file that faces one way throughout
  // on a few samples' say: hippo1 with every normal inward had 5,064 of its 6,104 turned
  // outward, its head left inward.
  std::vector<char> odd_weighs(count, 0), even_weighs(count, 0);
  for (std::size_t p = 0; p < count; ++p)
    if (patch_size[p] >= kFewestPerPatch) (side[p] ? odd_weighs : even_weighs)[std::size_t(group[p])] = 1;
  const auto weighs = [&](std::size_t g) { return odd_weighs[g] && even_weighs[g]; };
  std::vector<FacingVote> vote(count);  // with the root patch's side kept
  std::vector<Enclosure> encloses(count);  // likewise
  std::vector<glm::dvec3> odd_facing(count, glm::dvec3(0.0)), even_facing(count, glm::dvec3(0.0));
  for (std::size_t i = 0; i < n; ++i) {
    const auto p = std::size_t(patch[i]);
    const auto g = std::size_t(group[p]);
    if (!weighs(g)) continue;
    vote[g].add(points[i], side[p] ? -normals[i] : normals[i], inv_h2[i], ProjectionStatus::converged);
    encloses[g].add(points[i], side[p] ? -normals[i] : normals[i], 1.0 / double(inv_h2[i]));
    (side[p] ? odd_facing : even_facing)[g] += glm::dvec3(normals[i]) / double(inv_h2[i]);
  }
  // Which side of each group turns.
  enum class Turn : char { even, odd, neither };
  std::vector<Turn> turn(count);
  for (std::size_t g = 0; g < count; ++g) {
    const int facing = vote[g].sign() != 0 ? vote[g].sign() : encloses[g].sign();
    if (!weighs(g))
      turn[g] = Turn::neither;
    else if (facing != 0)
      turn[g] = facing > 0 ? Turn::odd : Turn::even;
    else if (glm::dot(odd_facing[g], even_facing[g]) >= 0)
      turn[g] = Turn::neither;
    else
      turn[g] = odd[g] <= even[g] ? Turn::odd : Turn::even;  // ties keep the root patch's side
  }
  std::vector<char> turned_by_groups(count);
  for (std::size_t p = 0; p < count; ++p) {
    const Turn t = turn[std::size_t(group[p])];
    turned_by_groups[p] = t != Turn::neither && (t == Turn::odd) == bool(side[p]);
  }
  for (std::size_t i = 0; i < n; ++i)
    if (turned_by_groups[std::size_t(patch[i])]) normals[i] = -normals[i];
  return turn_stragglers(turned_by_groups);
}

}  // namespace pss
