// The seams' turn of the samples' oriented normals tile by tile (points/seam_turn.hpp), in
// the in-core turn's three steps, each a pass over the tiles: (1) each tile joins its own
// samples to their neighbours' patches, and the joins are united over the cloud, each patch
// numbered by its least sample, as in core; (2) each tile weighs the evidence between the
// patches its own samples see, and the sums link the patches into groups, whose samples vote
// (read from the oriented records) on which side turns; (3) where patches of a few samples
// straggle, each tile sums their samples' says with the groups' turn made. What is held for
// the whole cloud: a patch number a point (4 bytes) while the turn runs, and a byte a point
// after it where it turned any.
#include <algorithm>

#include "pss/core/error.hpp"
#include "pss/core/progress.hpp"
#include "tile_bytes.hpp"
#include "tiled_samples.hpp"

namespace pss {

namespace {

// The cloud's samples' patches: a union-find over the points whose root is its least member,
// then each point's patch numbered by its root in the cloud's order; kNoPatch where the
// point is no sample.
class CloudPatches {
 public:
  explicit CloudPatches(std::uint64_t points) : of_(std::size_t(points), kNoPatch) {
    if (points >= kNoPatch) throw Error("the seams' turn tile by tile numbers at most 2^32 - 1 points");
  }
  void sample(std::uint64_t i) { of_[std::size_t(i)] = std::uint32_t(i); }
  void join(std::uint64_t a, std::uint64_t b) {
    std::uint32_t ra = root(std::uint32_t(a)), rb = root(std::uint32_t(b));
    if (ra == kNoPatch || rb == kNoPatch || ra == rb) return;
    if (ra > rb) std::swap(ra, rb);
    of_[rb] = ra;
  }
  // Once the joins are done: every sample's root lies before it, so one pass in order finds
  // its root's number already written. Returns how many patches there are.
  std::size_t number() {
    std::uint32_t patches = 0;
    for (std::size_t i = 0; i < of_.size(); ++i) {
      if (of_[i] == kNoPatch) continue;
      of_[i] = of_[i] == std::uint32_t(i) ? patches++ : of_[of_[i]];
    }
    return patches;
  }
  std::uint32_t operator[](std::uint64_t i) const { return of_[std::size_t(i)]; }

 private:
  std::uint32_t root(std::uint32_t i) {
    if (of_[i] == kNoPatch) return kNoPatch;
    while (of_[i] != i) {
      of_[i] = of_[of_[i]];  // path halving
      i = of_[i];
    }
    return i;
  }
  std::vector<std::uint32_t> of_;
};

// Each own record (a sample) of every tile.
template <class F>
void for_each_sample(const OrientedInTiles& samples, int tiles, F&& f) {
  for (int t = 0; t < tiles; ++t) samples.by_tile->for_each_record<Oriented>(t, f);
}

}  // namespace

std::size_t turn_seams_in_tiles(const UnitSets& sets, OrientedInTiles& samples, TileFarm& farm) {
  const TiledCloud& cloud = sets.cloud;
  const std::vector<int> tiles = cloud.tiles_with_points();
  CloudPatches patch(cloud.size());
  std::uint64_t sample_count = 0;
  for_each_sample(samples, cloud.tiles(), [&](const Oriented& r) {
    patch.sample(r.index);
    ++sample_count;
  });
  // A pass over the tiles, each asked for `step` with its points' patches (or whether they
  // are settled) where `per_point` gives them; `take` gets the result and the set's indices.
  const auto pass = [&](const char* label, SeamStep step, auto&& per_point, auto&& take) {
    Progress progress(label, std::int64_t(cloud.size()));
    farm.run(
        TileStep::seam_turn, tiles,
        [&](int t) {
          UnitSet set = sets.load(t);
          set.normals = normals_of_set(samples, sets, t, set);
          std::vector<std::uint32_t> patches;
          std::vector<char> settled;
          per_point(set.points.index, patches, settled);
          ByteWriter notes;
          notes.put_array<std::uint64_t>(set.points.index);
          notes.put(std::uint64_t(set.points.own));
          return TileRequest{seam_turn_request(unit_tile(set), step, patches, settled), notes.take()};
        },
        [&](int, std::span<const std::byte> result, std::span<const std::byte> notes, int) {
          ByteReader read(notes);
          const std::vector<std::uint64_t> index = read.get_array<std::uint64_t>();
          take(seam_turn_result(result, step), index);
          progress.advance(std::int64_t(read.get<std::uint64_t>()));
        });
  };
  const auto in_set = [](const std::vector<std::uint64_t>& index, int i) {
    if (i < 0 || std::size_t(i) >= index.size()) throw Error("a tile's seams' turn does not hold together");
    return index[std::size_t(i)];
  };
  const auto nothing = [](const std::vector<std::uint64_t>&, std::vector<std::uint32_t>&, std::vector<char>&) {};
  pass("seams' patches", SeamStep::joins, nothing,
       [&](const TileSeamTurn& done, const std::vector<std::uint64_t>& index) {
         for (std::size_t k = 0; k < done.joined.size(); ++k)
           patch.join(in_set(index, done.joined[k]), in_set(index, done.root[k]));
       });
  const std::size_t patches = patch.number();
  // As in core: normals so scattered that they form no patches of a few samples weigh nothing.
  if (patches > sample_count / kFewestPerPatch) return 0;
  std::vector<std::uint64_t> patch_size(patches, 0);
  for_each_sample(samples, cloud.tiles(), [&](const Oriented& r) { ++patch_size[patch[r.index]]; });
  PatchEvidence between;
  pass(
      "seams' evidence", SeamStep::evidence,
      [&](const std::vector<std::uint64_t>& index, std::vector<std::uint32_t>& patches, std::vector<char>&) {
        for (const std::uint64_t i : index) patches.push_back(patch[i]);
      },
      [&](const TileSeamTurn& done, const std::vector<std::uint64_t>&) {
        for (const auto& [key, e] : done.evidence)
          if (std::max(key >> 32, key & 0xffffffffu) >= patches)
            throw Error("a tile's seams' turn does not hold together");
        add_to(between, done.evidence);
      });
  PatchGroups groups(patch_size, between);
  between.clear();
  std::vector<char> turned_by_groups(patches, 0);
  const auto mark = [&](std::span<const char> turn) {  // samples.seam from a turn per patch
    samples.seam.clear();
    if (std::find(turn.begin(), turn.end(), char(1)) == turn.end()) return;
    samples.seam.assign(std::size_t(cloud.size()), 0);
    for_each_sample(samples, cloud.tiles(), [&](const Oriented& r) { samples.seam[r.index] = turn[patch[r.index]]; });
  };
  if (groups.linked()) {
    for_each_sample(samples, cloud.tiles(), [&](const Oriented& r) {
      const float h = sets.h[std::size_t(r.index)];
      groups.add(patch[r.index], r.point, samples.turned(r) ? -r.normal : r.normal, 1.0f / (h * h));
    });
    turned_by_groups = groups.turns();
    mark(turned_by_groups);
  }
  // Patches too small for the evidence face as the surfaces they lie on, the groups' turn made.
  std::vector<char> turn = turned_by_groups;
  if (std::any_of(patch_size.begin(), patch_size.end(), [](std::uint64_t s) { return s < kFewestPerPatch; })) {
    StragglerSays says(patches);
    pass(
        "seams' stragglers", SeamStep::stragglers,
        [&](const std::vector<std::uint64_t>& index, std::vector<std::uint32_t>&, std::vector<char>& settled) {
          for (const std::uint64_t i : index)
            settled.push_back(patch[i] != kNoPatch && patch_size[patch[i]] >= kFewestPerPatch);
        },
        [&](const TileSeamTurn& done, const std::vector<std::uint64_t>& index) {
          for (std::size_t k = 0; k < done.straggler.size(); ++k) {
            const std::uint32_t p = patch[in_set(index, done.straggler[k])];
            if (p == kNoPatch) throw Error("a tile's seams' turn does not hold together");
            says.add(p, done.say[k]);
          }
        });
    const std::vector<char> stragglers = says.turns();
    for (std::size_t p = 0; p < patches; ++p) turn[p] = char((turn[p] != 0) != (stragglers[p] != 0));
  }
  // samples.seam so far holds the groups' turn, which samples.turned applied: mark the whole.
  std::size_t turned = 0;
  for (std::size_t p = 0; p < patches; ++p) turned += turn[p] ? std::size_t(patch_size[p]) : 0;
  mark(turn);
  return turned;
}

}  // namespace pss
