// Range queries where every sample has a support of its own (adaptive support, issue 26):
// sample i takes part at x when ‖x − p_i‖ ≤ ρ_i = κ·h_i, weighted by exp(−‖x − p_i‖²/h_i²).
// One uniform grid cannot serve widths that vary 60:1 (cells sized to the widest would hold
// thousands of the narrowest's samples), so the samples are binned by width in levels a
// factor 2 apart, each level a uniform grid with cells of half its largest ρ; a query walks
// every level's cells within that level's largest ρ. One global h makes one level: a plain
// uniform grid, as the paper's 3D neighbourhood texture.
#pragma once

#include <span>
#include <vector>

#include "pss/spatial/support_layout.hpp"
#include "pss/spatial/uniform_grid.hpp"

namespace pss {

// One level: a uniform grid over the samples of widths in [2^l, 2^(l+1))·the least, whose
// cell_start holds offsets into the shared sorted points (GridView::points is those).
struct SupportLevel {
  GridView grid;
  float radius = 0;  // the largest ρ_i of the level's samples
};

// What kernels read, passed by value: the levels themselves are an array of their own (in
// the backend's memory), so that the view stays a few words however many levels there are
// (a kernel's by-value views that a thread takes the address of are copied to its stack).
struct SupportGridView {
  static constexpr int kMaxLevels = kSupportLevels;

  const vec3* points = nullptr;   // sorted by level, then by cell
  const float* inv_h2 = nullptr;  // 1/h_i² of each sorted sample
  // Unit normals of the sorted samples, consistently oriented: what APSS and RIMLS fit
  // (points/algebraic_sphere.hpp, points/robust_implicit.hpp); null for the paper's MLS.
  const vec3* normals = nullptr;
  // How many points each sorted sample stands for (points/merged_samples.hpp): its weight's
  // factor; null where every sample is one point.
  const float* mass = nullptr;
  const SupportLevel* level = nullptr;
  int levels = 0;
  int count = 0;
  float kappa2 = 4;  // (ρ_i/h_i)²: sample i covers x when ‖x − p_i‖²/h_i² ≤ kappa2

  // f(point, sorted index) for every sample of the cells within each level's largest ρ of
  // c: those that cover c and more, for callers that test (covers) without branching.
  template <class F>
  PSS_HOST_DEVICE void for_each_near(vec3 c, F&& f) const {
    for (int l = 0; l < levels; ++l) level[l].grid.for_each_near(c, level[l].radius, f);
  }

  PSS_HOST_DEVICE bool covers(int i, float distance2) const { return distance2 * inv_h2[i] <= kappa2; }
  PSS_HOST_DEVICE float mass_of(int i) const { return mass ? mass[i] : 1.0f; }

  // f(point, squared distance, sorted index) for every sample whose support holds c.
  template <class F>
  PSS_HOST_DEVICE void for_each_covering(vec3 c, F&& f) const {
    for_each_near(c, [&](vec3 p, int i) {
      const float d2 = length2(p - c);
      if (covers(i, d2)) f(p, d2, i);
    });
  }

  // The sorted index of the sample nearest c among those whose support holds it; −1 where
  // none does.
  PSS_HOST_DEVICE int nearest_covering(vec3 c) const {
    float nearest = kInfinity;
    int index = -1;
    for_each_covering(c, [&](vec3, float d2, int i) {
      if (d2 < nearest) {
        nearest = d2;
        index = i;
      }
    });
    return index;
  }
};

class SupportGrid {
 public:
  // h[i] > 0 is point i's width, kappa = ρ_i/h_i. Each level's grid has at most 32 cells per
  // sample (4,096 at least) and at most max_cells (UniformGrid).
  SupportGrid(std::span<const vec3> points, std::span<const float> h, float kappa, long long max_cells = 1ll << 25);
  // The grid of points subset[0], subset[1], ... alone, without copying them out first (the
  // samples kept of a cloud); ties within a cell go by their order in `subset`, and
  // original_index() counts in `points`.
  SupportGrid(std::span<const vec3> points, std::span<const float> h, std::span<const int> subset, float kappa,
              long long max_cells = 1ll << 25);
  // The same on a given layout (a tile's samples on the whole cloud's, support_layout.hpp):
  // each level the part of the layout's lattice its samples occupy; every width at least the
  // layout's least. A query that every sample covering it is among these (a tile's halo)
  // walks them in the whole cloud's grid's order, where ties within a cell go by their order
  // in `subset` there as here.
  SupportGrid(std::span<const vec3> points, std::span<const float> h, std::span<const int> subset,
              const SupportLayout& layout);

  SupportGrid(const SupportGrid&) = delete;  // the levels point into the arrays
  SupportGrid& operator=(const SupportGrid&) = delete;
  SupportGrid(SupportGrid&&) = default;  // vectors keep their buffers when moved
  SupportGrid& operator=(SupportGrid&&) = default;

  SupportGridView view() const;  // on the host
  std::span<const vec3> sorted_points() const { return sorted_; }
  std::span<const float> inv_h2() const { return inv_h2_; }
  // The samples' oriented unit normals in sorted order (points/sample_normals.hpp), or none.
  std::span<const vec3> normals() const { return normals_; }
  void set_normals(std::vector<vec3> sorted_normals);
  // Where samples stand for several points (points/merged_samples.hpp): into[i], per point
  // the grid was built of, is the point whose sample point i joined (i itself for a sample).
  // Each sample's mass (SupportGridView::mass) is then how many points joined it, and
  // members(k) are sorted sample k's, ascending: what its file normal and colour are the
  // mean of. Points that joined a sample the grid does not hold (set aside) count nowhere.
  void set_members(std::span<const int> into);
  std::span<const float> masses() const { return mass_; }  // in sorted order; empty: one each
  std::span<const int> members(std::size_t k) const {  // empty where no sample was merged
    if (member_start_.empty()) return {};
    return {member_.data() + member_start_[k], member_.data() + member_start_[k + 1]};
  }
  std::span<const int> cell_starts() const { return cell_start_; }  // every level's, one after another
  // The levels as on the host; a level's cells begin at level_cell_offset()[l] in cell_starts().
  std::span<const SupportLevel> levels_on_host() const { return levels_; }
  std::span<const int> level_cell_offset() const { return level_offset_; }
  // original_index()[i] is the input index of sorted point i.
  std::span<const int> original_index() const { return original_index_; }
  int levels() const { return int(levels_.size()); }
  float kappa() const { return kappa_; }
  // The indices of `points` (any points, not the grid's) in the order of the first level's
  // cells, ties by index: queries in that order gather neighbouring samples one after another.
  std::vector<int> cell_order(std::span<const vec3> points) const;

 private:
  static void check_subset(std::span<const vec3> points, std::span<const int> subset);
  template <class Index>
  static SupportTally tally(std::span<const vec3> points, std::span<const float> h, std::size_t count, Index index);
  template <class Index>
  void build(std::span<const vec3> points, std::span<const float> h, std::size_t count, Index index,
             const SupportLayout& layout, bool part);

  std::vector<vec3> sorted_;
  std::vector<float> inv_h2_;
  std::vector<vec3> normals_;
  std::vector<float> mass_;
  std::vector<int> member_start_, member_;  // members(k): member_[member_start_[k] ..)
  std::vector<int> cell_start_;
  std::vector<int> level_offset_;
  std::vector<SupportLevel> levels_;
  std::vector<int> original_index_;
  float kappa_ = 2;
};

}  // namespace pss
