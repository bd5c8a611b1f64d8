#include "pss/tiles/project.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include "pss/backend/cpu/parallel_for.hpp"
#include "pss/backend/mirror.hpp"
#include "pss/backend/parallel_for.hpp"
#include "pss/core/error.hpp"
#include "pss/core/memory.hpp"
#include "pss/core/progress.hpp"
#include "pss/points/orient_normals.hpp"
#include "pss/points/outliers.hpp"
#include "pss/spatial/grid_mirror.hpp"
#include "pss/tiles/orient.hpp"
#include "pss/tiles/support.hpp"

namespace pss {

namespace {

struct Projected {  // a point projected, in its tile's bucket
  std::uint64_t index;
  vec3 point, normal;  // unit frame
  float radius;        // ρ_i, unit frame: the orientation links the samples of each N(p_i)
  ProjectionStatus status;
};

struct Oriented {  // a point oriented, in its window's bucket: its own tile's, or a halo's vote
  std::uint64_t index;
  vec3 point, normal;  // unit frame
  std::uint32_t piece;
  ProjectionStatus status;
  bool own;
};

// A tile and its halo in the unit frame, with each point's width and whether it is a sample.
struct UnitSet {
  TilePoints points;
  std::vector<vec3> unit;
  std::vector<float> h;
  std::vector<int> samples;  // indices into the set of the samples kept
};

UnitSet load_unit(const TiledCloud& cloud, int tile, double halo, const UnitFrame& frame,
                  const std::vector<float>& h, const std::vector<char>& kept) {
  UnitSet s{cloud.load(tile, float(halo)), {}, {}, {}};
  const std::size_t m = s.points.positions.size();
  s.unit.resize(m);
  s.h.resize(m);
  for (std::size_t i = 0; i < m; ++i) {
    s.unit[i] = frame.to_unit(s.points.positions[i]);
    const auto id = std::size_t(s.points.index[i]);
    s.h[i] = h[id];
    if (kept[id]) s.samples.push_back(int(i));
  }
  return s;
}

// The world halo that holds every sample within `unit_reach` of the tile's box, rounding aside.
double world_halo(double unit_reach, const UnitFrame& frame) { return unit_reach * frame.scale * (1 + 1e-5); }

}  // namespace

TiledProjection::TiledProjection(const TiledCloud& cloud, const ProjectionParams& params, Backend backend,
                                 const std::filesystem::path& folder, std::size_t window_points,
                                 std::size_t buffer_bytes, Stats& stats)
    : cloud_(cloud), window_points_(std::max<std::size_t>(window_points, 1)) {
  validate(params);
  if (params.surface != SurfaceOperator::mls)
    throw NotTiled("tile by tile, pss project fits the paper's MLS surface only (not APSS or RIMLS) so far");
  if (cloud.has_normals()) throw NotTiled("tile by tile, pss project does not take a file's normals so far");
  const std::uint64_t n = cloud.size();
  frame_ = unit_frame_of_box(glm::dvec3(cloud.bounds().lo), glm::dvec3(cloud.bounds().hi));
  check_neighbourhood(params, frame_.diagonal);
  ProjectionParams unit_params = params;
  unit_params.h = float(double(params.h) / frame_.scale);
  unit_params.rho = float(double(params.rho) / frame_.scale);
  unit_params.t_tolerance = float(double(params.t_tolerance) / frame_.scale);
  const float kappa = unit_params.rho / unit_params.h;

  // The widths, in the unit frame as in core.
  std::vector<float> h;
  {
    ScopedPhase phase(stats, "support widths", params.support == Support::global);
    SupportWidths widths = support_widths(cloud, params);
    widths_ = {{}, widths.least, widths.median, widths.largest};
    h = std::move(widths.h);
  }
  for (float& w : h) w = float(double(w) / frame_.scale);
  const double reach = double(kappa) * (n > 0 ? *std::max_element(h.begin(), h.end()) : 0.0f);  // the widest ρ_i

  // The outliers' passes (points/outliers.hpp): each sample's distance in its tile, then the
  // threshold over the whole cloud's.
  std::vector<char> kept(std::size_t(n), 1);
  if (params.outliers == OutlierPolicy::set_aside) {
    ScopedPhase phase(stats, "outliers", false);
    for (int pass = 0; pass < kOutlierPasses; ++pass) {
      std::vector<float> distance(std::size_t(n), std::numeric_limits<float>::quiet_NaN());
      Progress progress("outliers", std::int64_t(n));
      for (int t = 0; t < cloud.tiles(); ++t) {
        if (cloud.tile_size(t) == 0) continue;
        const UnitSet set = load_unit(cloud, t, world_halo(reach, frame_), frame_, h, kept);
        const SupportGrid grid(set.unit, set.h, set.samples, kappa);
        const std::span<const int> original = grid.original_index();
        std::vector<int> own;  // the tile's own samples, by sorted index
        for (std::size_t k = 0; k < original.size(); ++k)
          if (std::size_t(original[k]) < set.points.own) own.push_back(int(k));
        std::vector<float> out(original.size());
        const OutlierDistanceKernel kernel{grid.view(), out.data()};
        cpu::parallel_for(std::int64_t(own.size()), [&](std::int64_t m) { kernel(own[std::size_t(m)]); });
        for (const int k : own) distance[std::size_t(set.points.index[std::size_t(original[std::size_t(k)])])] = out[std::size_t(k)];
        progress.advance(std::int64_t(cloud.tile_size(t)));
      }
      if (pass == 0) outliers_.threshold = outlier_threshold(distance);  // the second keeps it, as in core
      std::int64_t set_aside = 0;
      for (std::size_t i = 0; i < std::size_t(n); ++i)
        if (kept[i] && !(distance[i] <= outliers_.threshold)) {
          kept[i] = 0;
          ++set_aside;
        }
      outliers_.set_aside += set_aside;
      if (set_aside == 0) break;
    }
  }

  // The projections, each tile's from its samples and its halo's: a projection reads the
  // samples covering the points it moves through, within ρ of them; a halo twice the widest ρ
  // holds them while no point moves farther than ρ, and doubles where one does.
  BucketFile projected(folder, cloud.tiles(), sizeof(Projected), buffer_bytes);
  double moved = 0;  // the farthest a point moved, unit frame
  {
    Progress progress("projecting", std::int64_t(n));
    for (int t = 0; t < cloud.tiles(); ++t) {
      if (cloud.tile_size(t) == 0) continue;
      for (double halo = 2 * reach;; halo *= 2) {
        const UnitSet set = load_unit(cloud, t, world_halo(halo, frame_), frame_, h, kept);
        const SupportGrid grid(set.unit, set.h, set.samples, kappa);
        const GridMirror g(backend, grid);
        // The own points in the grid's order, then those set aside: neighbouring threads
        // gather neighbouring samples, as in core (a file's random order costs a fifth).
        const std::size_t own = set.points.own;
        std::vector<int> order;
        order.reserve(own);
        std::vector<char> placed(own, 0);
        for (const int i : grid.original_index())
          if (std::size_t(i) < own) {
            order.push_back(i);
            placed[std::size_t(i)] = 1;
          }
        for (std::size_t i = 0; i < own; ++i)
          if (!placed[i]) order.push_back(int(i));
        std::vector<vec3> own_points(own);
        for (std::size_t k = 0; k < own; ++k) own_points[k] = set.unit[std::size_t(order[k])];
        const Mirror<vec3> points(backend, own_points);
        Mirror<ProjectedPoint> out(backend, own);
        parallel_for(backend, "projection", std::int64_t(own),
                     ProjectPointsKernel{g.view(), points.data(), nullptr, out.data(), unit_params}, stats, &progress);
        const std::vector<ProjectedPoint> done = out.take();
        double farthest = 0;
        for (std::size_t k = 0; k < own; ++k)
          farthest = std::max(farthest, double(glm::length(done[k].point - own_points[k])));
        if (farthest + reach > halo && set.unit.size() < n) continue;
        moved = std::max(moved, farthest);
        for (std::size_t k = 0; k < own; ++k) {
          const auto i = std::size_t(order[k]);
          const Projected r{set.points.index[i], done[k].point, done[k].normal, kappa * set.h[i], done[k].status};
          projected.append(t, &r);
          switch (r.status) {
            case ProjectionStatus::converged: ++counts_.converged; break;
            case ProjectionStatus::not_converged: ++counts_.not_converged; break;
            case ProjectionStatus::too_few_neighbours: ++counts_.too_few_neighbours; break;
            case ProjectionStatus::degenerate_normal: ++counts_.degenerate_normal; break;
          }
        }
        break;
      }
    }
  }
  projected.flush();
  release(h);
  release(kept);

  // The orientation (orient_normals.hpp), tile by tile: each tile's points with those of its
  // halo, every point linked to those within their ρ_j; each piece of it a sign to agree on.
  const std::size_t windows = std::size_t((n + window_points_ - 1) / window_points_);
  ordered_ = std::make_unique<BucketFile>(folder, int(std::max<std::size_t>(windows, 1)), sizeof(Oriented), buffer_bytes);
  PieceSigns signs;
  ScopedPhase orientation(stats, "orient normals", false);  // its Progress shows it
  {
    Progress progress("orient normals", std::int64_t(n));
    const double halo = world_halo(reach, frame_);
    for (int t = 0; t < cloud.tiles(); ++t) {
      if (cloud.tile_size(t) == 0) continue;
      std::vector<Projected> set;
      const Aabb box = cloud.tile_box(t);
      projected.read(t, [&](std::span<const char> block) {
        for (std::size_t k = 0; k < block.size(); k += sizeof(Projected)) {
          Projected r;
          std::memcpy(&r, block.data() + k, sizeof r);
          set.push_back(r);
        }
      });
      const std::size_t own = set.size();
      // A halo's point lies within `moved` of its own tile's box.
      for (const int other : cloud.tiles_near(t, float(halo + world_halo(moved, frame_))))
        projected.read(other, [&](std::span<const char> block) {
          for (std::size_t k = 0; k < block.size(); k += sizeof(Projected)) {
            Projected r;
            std::memcpy(&r, block.data() + k, sizeof r);
            if (distance_to_box(frame_.from_unit(r.point), box) <= halo) set.push_back(r);
          }
        });
      std::sort(set.begin() + std::ptrdiff_t(own), set.end(),
                [](const Projected& a, const Projected& b) { return a.index < b.index; });
      std::vector<vec3> points(set.size()), normals(set.size());
      std::vector<float> radius(set.size());
      std::vector<std::uint64_t> id(set.size());
      for (std::size_t i = 0; i < set.size(); ++i) {
        points[i] = set[i].point;
        normals[i] = set[i].normal;
        radius[i] = set[i].radius;
        id[i] = set[i].index;
      }
      const OrientedParts parts = orient_normals_in_parts(points, normals, radius, id);
      std::vector<std::uint32_t> piece(parts.root.size());
      for (std::size_t p = 0; p < piece.size(); ++p) {
        const auto root = std::size_t(parts.root[p]);
        piece[p] = signs.add_piece(points[root].z, id[root]);
      }
      for (std::size_t i = 0; i < set.size(); ++i) {
        const Oriented r{id[i], points[i], normals[i], piece[std::size_t(parts.of_point[i])], set[i].status, i < own};
        ordered_->append(int(id[i] / window_points_), &r);
      }
      progress.advance(std::int64_t(own));
    }
  }
  ordered_->flush();

  // The votes: each halo point's normal against its own tile's, window by window.
  for (int w = 0; w < ordered_->buckets(); ++w) {
    const std::uint64_t first = std::uint64_t(w) * window_points_;
    const std::size_t size = std::size_t(std::min<std::uint64_t>(window_points_, n - first));
    std::vector<vec3> normal(size);
    std::vector<std::uint32_t> piece(size);
    auto each = [&](bool own, auto&& f) {
      ordered_->read(w, [&](std::span<const char> block) {
        for (std::size_t k = 0; k < block.size(); k += sizeof(Oriented)) {
          Oriented r;
          std::memcpy(&r, block.data() + k, sizeof r);
          if (r.own == own) f(r);
        }
      });
    };
    each(true, [&](const Oriented& r) {
      normal[r.index - first] = r.normal;
      piece[r.index - first] = r.piece;
    });
    each(false, [&](const Oriented& r) {
      signs.vote(r.piece, piece[r.index - first], glm::dot(r.normal, normal[r.index - first]) >= 0);
    });
  }
  flip_ = signs.turns();
}

void TiledProjection::read_in_order(const std::function<void(const ProjectedWindow&)>& f) const {
  const std::uint64_t n = cloud_.size();
  for (int w = 0; w < ordered_->buckets() && n > 0; ++w) {
    ProjectedWindow window;
    window.first = std::uint64_t(w) * window_points_;
    const std::size_t size = std::size_t(std::min<std::uint64_t>(window_points_, n - window.first));
    window.positions.resize(size);
    window.normals.resize(size);
    window.status.resize(size);
    ordered_->read(w, [&](std::span<const char> block) {
      for (std::size_t k = 0; k < block.size(); k += sizeof(Oriented)) {
        Oriented r;
        std::memcpy(&r, block.data() + k, sizeof r);
        if (!r.own) continue;
        const std::size_t i = std::size_t(r.index - window.first);
        window.positions[i] = frame_.from_unit(r.point);
        window.normals[i] = flip_[r.piece] ? -r.normal : r.normal;
        window.status[i] = r.status;
      }
    });
    f(window);
  }
}

}  // namespace pss
