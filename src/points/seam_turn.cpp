#include "pss/points/seam_turn.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include <omp.h>

#include "pss/fit/weights.hpp"

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

// Fixed point, as facing_vote.hpp's: the same sums in any order, so that tiles add up to the
// in-core sums. ρ² ≥ 2⁻⁴⁰ of the unit frame still counts; |x| is clamped to 2¹⁴.
constexpr double kScale = 0x1p48;
__int128 fixed(double x) {
  if (!std::isfinite(x)) return 0;
  return __int128(std::llround(std::clamp(x, -0x1p14, 0x1p14) * kScale));
}
long double real(__int128 x) { return static_cast<long double>(x); }

// Two neighbours: the squared distance in ρ_i, n_i·n_j, the larger squared offset along a
// normal over the squared distance, and −(e·n_i)(e·n_j)/|e|² for e = p_j − p_i: positive
// where the two agree on which side of each other they lie (each behind the other's face,
// or each before it), negative where one faces toward the other and the other away.
struct Pair {
  int j;
  float in_rho2, agreement, offset2, facing;
};

// f(pair, e) for sorted sample i's neighbours j ≠ i within its support ρ_i.
template <class F>
void for_each_neighbour(const SupportGridView& view, std::span<const vec3> normals, int i, F&& f) {
  const vec3 p_i = view.points[i];
  const vec3 n_i = normals[std::size_t(i)];
  view.for_each_near(p_i, [&](vec3 q, int j) {
    if (j == i) return;
    const vec3 e = q - p_i;
    const float d2 = glm::dot(e, e);
    if (!view.covers(i, d2) || d2 == 0) return;
    const float zi = glm::dot(e, n_i), zj = glm::dot(e, normals[std::size_t(j)]);
    Pair pair;
    pair.j = j;
    pair.in_rho2 = d2 * view.inv_h2[i] / view.kappa2;
    pair.agreement = glm::dot(n_i, normals[std::size_t(j)]);
    pair.offset2 = std::max(zi * zi, zj * zj) / d2;
    pair.facing = -zi * zj / d2;
    f(pair, e);
  });
}

// Patches a and b, flipped against each other (odd) or not, by this much more evidence.
struct Link {
  std::int64_t strength;
  int a, b, odd;
};

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

}  // namespace

void patch_joins(const SupportGridView& view, std::span<const vec3> normals, int i, std::vector<int>& joined) {
  joined.clear();
  for_each_neighbour(view, normals, i, [&](const Pair& p, vec3) {
    if (p.in_rho2 <= 0.25f && p.agreement > kAgree && p.offset2 < kSideBySide * kSideBySide) joined.push_back(p.j);
  });
}

// From sample i: where its opposed and agreeing neighbours lie in its tangent plane, the
// means of their unit directions. Along a seam the opposed ones lie to one side, and the
// agreeing ones all around or to the other; on a thin part the other face's samples surround
// i (their mean is short), or, at its rim, lie on the same side as i's own.
void add_evidence(const SupportGridView& view, std::span<const vec3> normals, std::span<const std::uint32_t> patch,
                  int i, PatchEvidence& tally) {
  thread_local std::vector<Pair> around;
  around.clear();
  const vec3 n_i = normals[std::size_t(i)];
  vec3 toward_opposed(0.0f), toward_agreeing(0.0f);
  int opposed = 0, agreeing = 0;
  for_each_neighbour(view, normals, i, [&](const Pair& p, vec3 e) {
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
  const std::uint32_t a = patch[std::size_t(i)];
  for (const Pair& p : around) {
    const std::uint32_t b = patch[std::size_t(p.j)];
    if (a == b || b == kNoPatch) continue;
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
}

void add_to(PatchEvidence& into, const PatchEvidence& from) {
  for (const auto& [key, e] : from) {
    into[key].flip += e.flip;
    into[key].keep += e.keep;
  }
}

EvidenceTallies::EvidenceTallies() : tallies_(std::size_t(std::max(1, omp_get_max_threads()))) {}

void EvidenceTallies::add(const SupportGridView& view, std::span<const vec3> normals,
                          std::span<const std::uint32_t> patch, int i) {
  add_evidence(view, normals, patch, i, tallies_[std::size_t(omp_get_thread_num())]);
}

PatchEvidence EvidenceTallies::sum() const {
  PatchEvidence between;
  for (const PatchEvidence& tally : tallies_) add_to(between, tally);
  return between;
}

// A straggler is such as a sample on a crease whose normal lies between its faces' (a CAD
// file's): it agrees with no neighbour within 45°, and its pairs with them are neither side by
// side nor plainly one behind the other's face, so they weigh nothing or mislead (cube.pwn:
// six left inward on its slots' edges cut five holes in its mesh). A thin part's other face
// does not pass through the sample, and so has no say.
double straggler_say(const SupportGridView& view, std::span<const vec3> normals, std::span<const char> settled, int i) {
  const vec3 p_i = view.points[i];
  vec3 around(0.0f);
  view.for_each_near(p_i, [&](vec3 q, int j) {
    const vec3 e = q - p_i;
    const float d2 = glm::dot(e, e);
    if (!view.covers(i, d2) || d2 == 0 || !settled[std::size_t(j)]) return;
    const vec3 n_j = normals[std::size_t(j)];
    const float z = glm::dot(e, n_j);
    if (z * z < kSideBySide * kSideBySide * d2) around += gaussian_weight(d2, view.inv_h2[i]) * n_j;
  });
  return double(glm::dot(around, normals[std::size_t(i)]));
}

PatchGroups::PatchGroups(std::span<const std::uint64_t> patch_size, const PatchEvidence& between) {
  std::vector<Link> links;
  for (const auto& [key, e] : between) {
    const int a = int(key >> 32), b = int(key & 0xffffffffu);
    if (e.flip >= 2 && e.flip > 2 * e.keep) links.push_back({e.flip - e.keep, a, b, 1});
    if (e.keep >= 2 && e.keep > 2 * e.flip) links.push_back({e.keep - e.flip, a, b, 0});
  }
  linked_ = !links.empty();
  if (!linked_) return;
  std::sort(links.begin(), links.end(), [](const Link& x, const Link& y) {
    return x.strength != y.strength ? x.strength > y.strength : (x.a != y.a ? x.a < y.a : x.b < y.b);
  });
  const std::size_t count = patch_size.size();
  ParityUnionFind flips(count);
  for (const Link& l : links) flips.link(l.a, l.b, l.odd);
  group_.resize(count);
  side_.resize(count);
  for (std::size_t k = 0; k < count; ++k) group_[k] = flips.find(int(k), side_[k]);
  // A group shows a flip only where both its sides hold a patch large enough to weigh; one
  // whose other side is stragglers (fewer than kFewestPerPatch samples a patch) does not: the
  // stragglers' turn settles those. Its vote would turn a file that faces one way throughout
  // on a few samples' say: hippo1 with every normal inward had 5,064 of its 6,104 turned
  // outward, its head left inward.
  std::vector<char> odd_weighs(count, 0), even_weighs(count, 0);
  for (std::size_t p = 0; p < count; ++p)
    if (patch_size[p] >= kFewestPerPatch) (side_[p] ? odd_weighs : even_weighs)[std::size_t(group_[p])] = 1;
  weighing_.assign(count, -1);
  for (std::size_t g = 0; g < count; ++g)
    if (odd_weighs[g] && even_weighs[g]) {
      weighing_[g] = int(sums_.size());
      sums_.emplace_back();
    }
}

void PatchGroups::add(std::uint32_t patch, vec3 p, vec3 normal, float inv_h2) {
  if (!linked_) return;
  const int w = weighing_[std::size_t(group_[patch])];
  if (w < 0) return;
  Sums& s = sums_[std::size_t(w)];
  const int side = side_[patch];
  const vec3 kept = side ? -normal : normal;  // with the root patch's side kept
  s.vote.add(p, kept, inv_h2, ProjectionStatus::converged);
  const double area = 1.0 / double(inv_h2);
  s.area += fixed(area);
  s.outward += fixed(area * glm::dot(glm::dvec3(p), glm::dvec3(kept)));
  for (int a = 0; a < 3; ++a) {
    s.normal[a] += fixed(area * double(kept[a]));
    s.position[a] += fixed(area * double(p[a]));
    s.facing[side][a] += fixed(area * double(normal[a]));
  }
  s.count[side] += 1;
}

// Whether a group, its odd side turned, encloses a volume, where its vote on heights has no
// say (facing_vote.hpp: the dragon's true normals give 0.28 of their magnitudes there, near
// the quarter it asks): by the divergence theorem in all three axes, Σ (p − c)·n ρ² = 3V about
// any c, so a closed surface (|Σ n ρ²| under a tenth of Σ ρ²: the bunny, its base open, 0.04)
// faces outward where the sum about the centroid c is positive (the patches of a group face
// consistently, whichever side they keep). Open surfaces (the ground and its roofs: |Σ n ρ²|
// near Σ ρ²) have no say.
int PatchGroups::enclosure_sign(const Sums& s) const {
  constexpr long double kClosed = 0.1L;
  const long double area = real(s.area);
  long double normal2 = 0, centred = 0;
  for (int a = 0; a < 3; ++a) normal2 += real(s.normal[a]) * real(s.normal[a]);
  if (!(area > 0) || !(std::sqrt(normal2) <= kClosed * area)) return 0;
  for (int a = 0; a < 3; ++a) centred += real(s.position[a]) / area * real(s.normal[a]);
  const long double volume = real(s.outward) - centred;
  return volume > 0 ? 1 : (volume < 0 ? -1 : 0);
}

// Each group of linked patches whose sides both hold a patch that weighs turns one side: the
// one that faces inward as the whole group votes with the other's sign (facing_vote.hpp), or
// where that vote has no say, as the volume the group encloses says (enclosure_sign), or where
// neither has (an open surface seen edge-on), the smaller side, if the two sides face opposite
// ways (their normals' sums): a sheet half flipped. Where they face alike the links do not show
// a flip, and nothing turns. A file's majority is no guide: cube.pwn's normals, each signed
// positive along its axis, point inward on the three faces that hold more samples, and the
// majority turned the whole part inward.
std::vector<char> PatchGroups::turns() const {
  enum class Turn : char { even, odd, neither };
  std::vector<Turn> turn(sums_.size());
  for (std::size_t w = 0; w < sums_.size(); ++w) {
    const Sums& s = sums_[w];
    const int vote = s.vote.sign();
    const int facing = vote != 0 ? vote : enclosure_sign(s);
    long double alike = 0;
    for (int a = 0; a < 3; ++a) alike += real(s.facing[0][a]) * real(s.facing[1][a]);
    if (facing != 0)
      turn[w] = facing > 0 ? Turn::odd : Turn::even;
    else if (alike >= 0)
      turn[w] = Turn::neither;
    else
      turn[w] = s.count[1] <= s.count[0] ? Turn::odd : Turn::even;  // ties keep the root patch's side
  }
  std::vector<char> turned(group_.size(), 0);
  for (std::size_t p = 0; p < group_.size(); ++p) {
    const int w = weighing_[std::size_t(group_[p])];
    if (w < 0) continue;
    const Turn t = turn[std::size_t(w)];
    turned[p] = t != Turn::neither && (t == Turn::odd) == bool(side_[p]);
  }
  return turned;
}

void StragglerSays::add(std::uint32_t patch, double say) { say_[patch] += fixed(say); }

std::vector<char> StragglerSays::turns() const {
  std::vector<char> turn(say_.size());
  for (std::size_t p = 0; p < say_.size(); ++p) turn[p] = say_[p] < 0;
  return turn;
}

}  // namespace pss
