#include "tile_works.hpp"

#include <algorithm>
#include <limits>

#include "pss/backend/cpu/parallel_for.hpp"
#include "pss/backend/mirror.hpp"
#include "pss/backend/parallel_for.hpp"
#include "pss/core/gather.hpp"
#include "pss/core/stats.hpp"
#include "pss/points/outliers.hpp"
#include "pss/points/sample_normals.hpp"
#include "pss/points/noise.hpp"
#include "pss/points/spacing.hpp"
#include "pss/spatial/grid_mirror.hpp"
#include "pss/spatial/support_grid.hpp"
#include "pss/spatial/uniform_grid.hpp"
#include "tile_arrays.hpp"
#include "tile_bytes.hpp"

namespace pss {

std::vector<std::byte> own_points_notes(const TilePoints& points) {
  ByteWriter notes;
  notes.put_array(std::span(points.index).first(points.own));
  return notes.take();
}

std::vector<std::uint64_t> own_points(std::span<const std::byte> notes) {
  return ByteReader(notes).get_array<std::uint64_t>();
}

void put_tile(ByteWriter& out, const UnitTile& tile) {
  if (tile.layout == nullptr) throw Error("a tile's work needs the cloud's layout");
  out.put(*tile.layout);
  out.put(std::uint64_t(tile.own));
  out.put_array(tile.unit);
  out.put_array(tile.h);
  out.put_array(tile.samples);
  out.put_array(tile.sample_at);
  out.put_array(tile.into);
  out.put_array(tile.normals);
}

TileArrays get_tile(ByteReader& in) {
  TileArrays t{in.get<SupportLayout>(), std::size_t(in.get<std::uint64_t>()), in.get_array<vec3>(), in.get_array<float>(),
               in.get_array<int>(),    in.get_array<vec3>(),                 in.get_array<int>(),
               in.get_array<vec3>()};
  // SupportGrid refuses a sample outside the set; set_members trusts its cubes' first points.
  const std::size_t m = t.unit.size();
  bool whole = t.h.size() == m && t.own <= m && t.sample_at.size() == t.into.size() &&
               (t.into.empty() || t.into.size() == m) && (t.normals.empty() || t.normals.size() == m);
  for (const int i : t.into) whole = whole && i >= 0 && std::size_t(i) < m;
  if (!whole) throw Error("a tile's work does not hold together");
  return t;
}

SupportGrid grid_of_tile(const TileArrays& t) {
  SupportGrid grid(t.sample_at.empty() ? t.unit : t.sample_at, t.h, t.samples, t.layout);
  grid.set_members(t.into);
  if (!t.normals.empty()) grid.set_normals(gathered<vec3>(t.normals, grid.original_index()));
  return grid;
}

std::vector<int> own_sorted_samples(const SupportGrid& grid, std::size_t own) {
  std::vector<int> sorted;
  const std::span<const int> original = grid.original_index();
  for (std::size_t k = 0; k < original.size(); ++k)
    if (std::size_t(original[k]) < own) sorted.push_back(int(k));
  return sorted;
}

namespace {

// The projection of `points` onto the grid's surface, on `backend`.
std::vector<ProjectedPoint> project_on(const SupportGrid& grid, std::span<const vec3> points,
                                       std::span<const vec3> hints, const ProjectionParams& params, Backend backend) {
  const GridMirror g(backend, grid);
  const Mirror<vec3> at(backend, points);
  const Mirror<vec3> hint(backend, hints);
  Mirror<ProjectedPoint> out(backend, points.size());
  Stats stats;  // the caller times and shows the step whole
  parallel_for(backend, "projection", std::int64_t(points.size()),
               ProjectPointsKernel{g.view(), at.data(), hints.empty() ? nullptr : hint.data(), out.data(), params},
               stats, nullptr, false);
  return out.take();
}

}  // namespace

std::vector<std::byte> outliers_request(const UnitTile& tile) {
  ByteWriter out;
  put_tile(out, tile);
  return out.take();
}

// On the CPU, over the tile's own samples only (a GPU launch would measure the halo's too,
// whose kernel runs over every sample of a grid).
std::vector<std::byte> work_outliers(std::span<const std::byte> request) {
  ByteReader in(request);
  const TileArrays t = get_tile(in);
  const SupportGrid grid = grid_of_tile(t);
  const std::span<const int> original = grid.original_index();
  const std::vector<int> own = own_sorted_samples(grid, t.own);
  std::vector<float> out(original.size()), held_out(original.size());
  const OutlierDistanceKernel kernel{grid.view(), out.data(), held_out.data()};
  cpu::parallel_for(std::int64_t(own.size()), [&](std::int64_t m) { kernel(own[std::size_t(m)]); });
  std::vector<float> distance(t.own, std::numeric_limits<float>::quiet_NaN()), mass(distance), held(distance);
  const SupportGridView view = grid.view();
  for (const int k : own) {
    const auto i = std::size_t(original[std::size_t(k)]);
    distance[i] = out[std::size_t(k)];
    mass[i] = view.mass_of(k);
    held[i] = held_out[std::size_t(k)];
  }
  ByteWriter result;
  result.put_array<float>(distance);
  result.put_array<float>(mass);
  result.put_array<float>(held);
  return result.take();
}

TileOutliers outliers_result(std::span<const std::byte> result) {
  ByteReader in(result);
  TileOutliers o{in.get_array<float>(), in.get_array<float>(), in.get_array<float>()};
  if (o.mass.size() != o.distance.size() || o.held.size() != o.distance.size())
    throw Error("a tile's outliers do not hold together");
  return o;
}

std::vector<std::byte> projection_request(const UnitTile& tile, const ProjectionParams& unit_params, Backend backend,
                                          std::span<const vec3> file_normals) {
  ByteWriter out;
  put_tile(out, tile);
  out.put(unit_params);
  out.put(backend);
  out.put_array(file_normals);
  return out.take();
}

// MLS gathers N(r) once, at the point (points/surface_projection.hpp): the halo holds it.
std::vector<std::byte> work_projection(std::span<const std::byte> request) {
  ByteReader in(request);
  const TileArrays t = get_tile(in);
  const auto params = in.get<ProjectionParams>();
  const auto backend = in.get<Backend>();
  const std::vector<vec3> file_normals = in.get_array<vec3>();
  if (params.surface != SurfaceOperator::mls && t.normals.empty())
    throw Error("a tile's work does not hold together: APSS and RIMLS need the samples' normals");
  if (!file_normals.empty() && (file_normals.size() != t.unit.size() || t.normals.empty()))
    throw Error("a tile's work does not hold together: the file's normals need the samples' turned ones");
  const SupportGrid grid = grid_of_tile(t);
  // The own points in the grid's order, then the rest (set aside, or merged into samples) in
  // its cells' order: neighbouring threads gather neighbouring samples, as in core (a file's
  // random order costs a fifth).
  std::vector<int> order;
  order.reserve(t.own);
  std::vector<char> placed(t.own, 0);
  for (const int i : grid.original_index())
    if (std::size_t(i) < t.own) {
      order.push_back(i);
      placed[std::size_t(i)] = 1;
    }
  for (const int i : grid.cell_order(std::span<const vec3>(t.unit).first(t.own)))
    if (!placed[std::size_t(i)]) order.push_back(i);
  // The file's normals orient the projections, as in core (project_cloud.cpp): a sample's
  // turned one, and every other point's own on the side of its nearest sample's (where
  // samples were merged, every point's).
  std::vector<vec3> hints;
  for (std::size_t k = 0; k < order.size() && !file_normals.empty(); ++k) {
    const auto i = std::size_t(order[k]);
    hints.push_back(placed[i] && t.into.empty() ? t.normals[i]
                                                : hint_beside(grid.view(), grid.normals(), t.unit[i], file_normals[i]));
  }
  const std::vector<ProjectedPoint> done = project_on(grid, gathered<vec3>(t.unit, order), hints, params, backend);
  std::vector<vec3> point(done.size()), normal(done.size());
  std::vector<ProjectionStatus> status(done.size());
  for (std::size_t k = 0; k < done.size(); ++k) {
    point[k] = done[k].point;
    normal[k] = done[k].normal;
    status[k] = done[k].status;
  }
  ByteWriter result;  // array by array: a ProjectedPoint's padding is never sent
  result.put_array<int>(order);
  result.put_array<vec3>(point);
  result.put_array<vec3>(normal);
  result.put_array<ProjectionStatus>(status);
  return result.take();
}

TileProjections projection_result(std::span<const std::byte> result) {
  ByteReader in(result);
  TileProjections p{in.get_array<int>(), {}};
  const auto point = in.get_array<vec3>();
  const auto normal = in.get_array<vec3>();
  const auto status = in.get_array<ProjectionStatus>();
  if (point.size() != p.order.size() || normal.size() != p.order.size() || status.size() != p.order.size())
    throw Error("a tile's projections do not hold together");
  p.projected.resize(p.order.size());
  for (std::size_t k = 0; k < p.order.size(); ++k) p.projected[k] = {point[k], normal[k], status[k]};
  return p;
}

std::vector<std::byte> file_normals_request(const UnitTile& tile, std::span<const vec3> file_normals,
                                            std::span<const std::uint64_t> cloud_index) {
  ByteWriter out;
  put_tile(out, tile);
  out.put_array(file_normals);
  out.put_array(cloud_index);
  return out.take();
}

std::vector<std::byte> work_file_normals(std::span<const std::byte> request) {
  ByteReader in(request);
  const TileArrays t = get_tile(in);
  const std::vector<vec3> file_normals = in.get_array<vec3>();
  const std::vector<std::uint64_t> cloud_index = in.get_array<std::uint64_t>();
  if (file_normals.size() != t.unit.size() || cloud_index.size() != t.unit.size())
    throw Error("a tile's work does not hold together: a file normal and an index a point of the set");
  const SupportGrid grid = grid_of_tile(t);
  const std::span<const int> original = grid.original_index();
  const std::vector<int> sorted = own_sorted_samples(grid, t.own);
  std::vector<int> sample(sorted.size());
  std::vector<vec3> normal(sorted.size());
  std::vector<char> off(sorted.size());
  cpu::parallel_for(std::int64_t(sorted.size()), [&](std::int64_t m) {
    const auto k = std::size_t(sorted[std::size_t(m)]);
    sample[std::size_t(m)] = original[k];
    normal[std::size_t(m)] = file_normal_of(grid, file_normals, k, cloud_index);
    off[std::size_t(m)] = off_its_neighbours(grid.view(), int(k), normal[std::size_t(m)]);
  });
  ByteWriter result;
  result.put_array<int>(sample);
  result.put_array<vec3>(normal);
  result.put_array<char>(off);
  return result.take();
}

TileFileNormals file_normals_result(std::span<const std::byte> result) {
  ByteReader in(result);
  TileFileNormals f{in.get_array<int>(), in.get_array<vec3>(), in.get_array<char>()};
  if (f.normal.size() != f.sample.size() || f.off.size() != f.sample.size())
    throw Error("a tile's file normals do not hold together");
  return f;
}

std::vector<std::byte> sample_normals_request(const UnitTile& tile, const ProjectionParams& unit_params,
                                              Backend backend) {
  ByteWriter out;
  put_tile(out, tile);
  out.put(sample_plane_params(unit_params));
  out.put(backend);
  return out.take();
}

// At the samples' places in the grid (a merged one at its cube's mean), in its order.
std::vector<std::byte> work_sample_normals(std::span<const std::byte> request) {
  ByteReader in(request);
  const TileArrays t = get_tile(in);
  const auto params = in.get<ProjectionParams>();
  const auto backend = in.get<Backend>();
  const SupportGrid grid = grid_of_tile(t);
  const std::vector<int> sorted = own_sorted_samples(grid, t.own);  // their places in the grid
  const std::vector<int> sample = gathered<int>(grid.original_index(), sorted);  // and in the set
  const std::vector<ProjectedPoint> done =
      project_on(grid, gathered<vec3>(grid.sorted_points(), sorted), {}, params, backend);
  std::vector<vec3> normal(done.size());
  std::vector<ProjectionStatus> status(done.size());
  for (std::size_t k = 0; k < done.size(); ++k) {
    normal[k] = fitted_normal(done[k]);
    status[k] = done[k].status;
  }
  ByteWriter result;
  result.put_array<int>(sample);
  result.put_array<vec3>(normal);
  result.put_array<ProjectionStatus>(status);
  return result.take();
}

TileSampleNormals sample_normals_result(std::span<const std::byte> result) {
  ByteReader in(result);
  TileSampleNormals s{in.get_array<int>(), in.get_array<vec3>(), in.get_array<ProjectionStatus>()};
  if (s.normal.size() != s.sample.size() || s.status.size() != s.sample.size())
    throw Error("a tile's sample normals do not hold together");
  return s;
}

std::vector<std::byte> orientation_request(std::span<const vec3> points, std::span<const vec3> normals,
                                           std::span<const float> radius, std::span<const std::uint64_t> id,
                                           const Occupancy& occupancy, std::span<const int> sample) {
  ByteWriter out;
  out.put_array(points);
  out.put_array(normals);
  out.put_array(radius);
  out.put_array(id);
  out.put_array(sample);
  out.put(occupancy.box());
  out.put_array(occupancy.words());
  return out.take();
}

namespace {

// The tree's signs turned where the rays through `occupancy` say otherwise (visibility.hpp),
// in every part: the cloud's part, over the tiles, says whether they are taken. Per point,
// whether they turn it and its vote, as its normal faces after them; the points `silent`
// marks (where given) cast none.
struct SeenTurns {
  std::vector<char> turned;
  std::vector<std::int8_t> votes;
};

SeenTurns seen_turns(const Occupancy& occupancy, std::span<const vec3> points, std::span<const vec3> normals,
                     std::span<const float> rho, const SpanningTree& tree, std::span<const char> silent = {}) {
  std::vector<float> radius(rho.size());
  for (std::size_t i = 0; i < radius.size(); ++i) radius[i] = visibility_radius(rho[i]);
  SeenTurns seen{{}, visibility_votes(occupancy, points, normals, radius)};
  for (std::size_t i = 0; i < silent.size(); ++i)
    if (silent[i]) seen.votes[i] = 0;
  seen.turned = signs_along_tree(tree, seen.votes, kCutVotes);
  for (std::size_t i = 0; i < seen.votes.size(); ++i)
    if (seen.turned[i]) seen.votes[i] = std::int8_t(-seen.votes[i]);
  return seen;
}

}  // namespace

std::vector<std::byte> work_orientation(std::span<const std::byte> request) {
  ByteReader in(request);
  const auto points = in.get_array<vec3>();
  auto normals = in.get_array<vec3>();
  const auto radius = in.get_array<float>();
  const auto id = in.get_array<std::uint64_t>();
  const auto sample = in.get_array<int>();
  Occupancy occupancy(in.get<Aabb>());
  occupancy.set_words(in.get_array<std::uint64_t>());  // moved in: no copy beside the request's
  const std::size_t m = points.size();
  bool whole = normals.size() == m && radius.size() == m && id.size() == m && (sample.empty() || sample.size() == m);
  for (const int j : sample)
    whole = whole &&
            (j == -1 || j == kSampleNotInSet || (j >= 0 && std::size_t(j) < m && sample[std::size_t(j)] == -1));
  if (!whole) throw Error("a tile's work does not hold together");
  OrientedParts parts;
  SpanningTree tree;
  SeenTurns seen;
  if (sample.empty()) {
    parts = orient_normals_in_parts(points, normals, radius, id, &tree);
    seen = seen_turns(occupancy, points, normals, radius, tree);
  } else {  // the tree over the points that stand for themselves; the rest follow their samples'
    std::vector<int> nodes;
    for (std::size_t i = 0; i < m; ++i)
      if (sample[i] < 0) nodes.push_back(int(i));
    const std::vector<vec3> at = gathered<vec3>(points, nodes);
    std::vector<vec3> facing = gathered<vec3>(normals, nodes);
    const std::vector<float> rho = gathered<float>(radius, nodes);
    const std::vector<std::uint64_t> node_id = gathered<std::uint64_t>(id, nodes);
    const OrientedParts node_parts = orient_normals_in_parts(at, facing, rho, node_id, &tree);
    std::vector<char> silent(nodes.size());  // a halo's point whose sample the set lacks: no node in core
    for (std::size_t k = 0; k < nodes.size(); ++k) silent[k] = sample[std::size_t(nodes[k])] == kSampleNotInSet;
    const SeenTurns node_seen = seen_turns(occupancy, at, facing, rho, tree, silent);
    std::vector<int> node_of(m, -1);
    for (std::size_t k = 0; k < nodes.size(); ++k) {
      normals[std::size_t(nodes[k])] = facing[k];
      node_of[std::size_t(nodes[k])] = int(k);
    }
    parts.of_point.resize(m);
    seen.turned.resize(m);
    seen.votes.assign(m, 0);  // only the tree's points vote, as in core
    for (std::size_t i = 0; i < m; ++i) {
      const auto k = std::size_t(node_of[std::size_t(sample[i] < 0 ? int(i) : sample[i])]);
      parts.of_point[i] = node_parts.of_point[k];
      seen.turned[i] = node_seen.turned[k];
      if (sample[i] == -1) seen.votes[i] = node_seen.votes[k];
      if (sample[i] >= 0 && glm::dot(normals[i], normals[std::size_t(sample[i])]) < 0) normals[i] = -normals[i];
    }
    for (const int root : node_parts.root) parts.root.push_back(nodes[std::size_t(root)]);
  }
  ByteWriter result;
  result.put_array<vec3>(normals);
  result.put_array<int>(parts.of_point);
  result.put_array<int>(parts.root);
  result.put_array<char>(seen.turned);
  result.put_array<std::int8_t>(seen.votes);
  return result.take();
}

TileOrientation orientation_result(std::span<const std::byte> result, std::size_t points) {
  ByteReader in(result);
  TileOrientation o{in.get_array<vec3>(), {in.get_array<int>(), in.get_array<int>()}, in.get_array<char>(),
                    in.get_array<std::int8_t>()};
  bool whole = o.normals.size() == points && o.parts.of_point.size() == points && o.seen_turned.size() == points &&
               o.seen_votes.size() == points;
  for (const int part : o.parts.of_point) whole = whole && part >= 0 && std::size_t(part) < o.parts.root.size();
  for (const int root : o.parts.root) whole = whole && root >= 0 && std::size_t(root) < points;
  if (!whole) throw Error("a tile's orientation does not hold together");
  return o;
}

namespace {

void put_margin_tile(ByteWriter& out, const MarginTile& tile) {
  out.put(std::uint64_t(tile.own));
  out.put(tile.cloud_size);
  out.put(tile.scale);
  out.put_array(tile.unit);
  out.put_array(tile.id);
  out.put_array(tile.margin);
}

struct MarginArrays {
  std::size_t own;
  std::uint64_t cloud_size;
  double scale;
  std::vector<vec3> unit;
  std::vector<std::uint64_t> id;
  std::vector<float> margin;
  SampleSet set() const { return SampleSet{unit, id, margin, cloud_size, scale}; }
};

MarginArrays get_margin_tile(ByteReader& in) {
  MarginArrays t{std::size_t(in.get<std::uint64_t>()), in.get<std::uint64_t>(), in.get<double>(),
                 in.get_array<vec3>(), in.get_array<std::uint64_t>(), in.get_array<float>()};
  if (t.id.size() != t.unit.size() || (!t.margin.empty() && t.margin.size() != t.unit.size()) ||
      t.own > t.unit.size() || !(t.scale > 0))
    throw Error("a tile's work does not hold together");
  for (const std::uint64_t id : t.id)
    if (id >= t.cloud_size) throw Error("a tile's work does not hold together");
  return t;
}

std::vector<std::byte> incomplete() {
  ByteWriter out;
  out.put(std::uint8_t(0));
  return out.take();
}

}  // namespace

std::vector<std::byte> spacing_request(const MarginTile& tile, std::uint64_t stride) {
  ByteWriter out;
  put_margin_tile(out, tile);
  out.put(stride);
  return out.take();
}

std::vector<std::byte> work_spacing(std::span<const std::byte> request) {
  ByteReader in(request);
  const MarginArrays t = get_margin_tile(in);
  const auto stride = in.get<std::uint64_t>();
  if (stride == 0) throw Error("a tile's work does not hold together");
  SupportSteps steps(t.set());
  // query_spacing looks farther until it finds k neighbours: none here yet.
  if (t.unit.size() <= std::size_t(steps.k())) return incomplete();
  steps.measure_spacing(false);
  for (std::size_t i = 0; i < t.own; ++i)
    if (!steps.complete(i)) return incomplete();  // before the noise's grid: this halo is too narrow anyway
  const UniformGrid grid(t.unit, 1e-7f, std::max<long long>(4096, (long long)t.unit.size()));
  const GridView view = grid.view();
  const float cell = 1.0f / view.inv_cell;
  const NoiseGrids noise(t.unit, view);
  std::vector<float> measured(t.own);
  std::vector<char> held(t.own, 1);
  cpu::parallel_for(std::int64_t(t.own), [&](std::int64_t s) {
    const auto i = std::size_t(s);
    if (t.id[i] % stride == 0) {
      const QuerySpacing q = query_spacing(view, cell, t.unit[i], steps.k(), &noise.views());
      measured[i] = measured_noise(q);
      held[i] = t.margin.empty() || q.reach <= t.margin[i];
    }
  });
  if (!std::all_of(held.begin(), held.end(), [](char c) { return c != 0; })) return incomplete();
  TileSpacing s;
  s.spacing.assign(steps.spacing().begin(), steps.spacing().begin() + std::ptrdiff_t(t.own));
  s.least.assign(steps.least().begin(), steps.least().begin() + std::ptrdiff_t(t.own));
  for (std::size_t i = 0; i < t.own; ++i) {
    s.row_like += steps.row_like(i);
    if (t.id[i] % stride == 0) {
      s.query.push_back(t.id[i] / stride);
      s.at.push_back(t.unit[i]);
      s.measured.push_back(measured[i]);
    }
  }
  ByteWriter out;
  out.put(std::uint8_t(1));
  out.put_array<float>(s.spacing);
  out.put_array<float>(s.least);
  out.put(s.row_like);
  out.put_array<std::uint64_t>(s.query);
  out.put_array<vec3>(s.at);
  out.put_array<float>(s.measured);
  return out.take();
}

TileSpacing spacing_result(std::span<const std::byte> result, std::size_t own) {
  ByteReader in(result);
  TileSpacing s;
  s.complete = in.get<std::uint8_t>() != 0;
  if (!s.complete) return s;
  s.spacing = in.get_array<float>();
  s.least = in.get_array<float>();
  s.row_like = in.get<std::uint64_t>();
  s.query = in.get_array<std::uint64_t>();
  s.at = in.get_array<vec3>();
  s.measured = in.get_array<float>();
  if (s.spacing.size() != own || s.least.size() != own || s.at.size() != s.query.size() ||
      s.measured.size() != s.query.size())
    throw Error("a tile's spacings do not hold together");
  return s;
}

std::vector<std::byte> widths_request(const MarginTile& tile, const WidthsInputs& inputs) {
  ByteWriter out;
  put_margin_tile(out, tile);
  out.put_array(inputs.spacing);
  out.put_array(inputs.least);
  out.put(inputs.median_spacing);
  out.put(inputs.h);
  out.put(inputs.widest);
  out.put(inputs.kappa);
  out.put_array(inputs.noise_at);
  out.put_array(inputs.noise_measured);
  return out.take();
}

std::vector<std::byte> work_widths(std::span<const std::byte> request) {
  ByteReader in(request);
  const MarginArrays t = get_margin_tile(in);
  auto spacing = in.get_array<float>();
  auto least = in.get_array<float>();
  const auto median = in.get<float>(), h = in.get<float>(), widest = in.get<float>(), kappa = in.get<float>();
  auto at = in.get_array<vec3>();
  auto measured = in.get_array<float>();
  if (spacing.size() != t.unit.size() || least.size() != t.unit.size() || measured.size() != at.size())
    throw Error("a tile's work does not hold together");
  SupportSteps steps(t.set());
  steps.use_spacing(std::move(spacing), std::move(least));
  steps.find_wide(median);
  for (std::size_t i = 0; i < t.own; ++i)
    if (!steps.complete(i)) return incomplete();
  const RegionalNoise noise(std::move(at), std::move(measured));
  std::vector<float> width(t.own);
  std::vector<char> merged(t.own);
  const float cloud_noise = noise_of_h(h, median);
  cpu::parallel_for(std::int64_t(t.own), [&](std::int64_t s) {
    const auto i = std::size_t(s);
    width[i] = adaptive_width(h, widest, steps.wide(i), steps.spacing()[i], median, noise.about(t.unit[i]), t.scale);
    const float sigma = std::max(cloud_noise, float(double(noise.measured_about(t.unit[i])) * t.scale));
    merged[i] = merges_samples(width[i], steps.spacing()[i], sigma, kappa);
  });
  ByteWriter out;
  out.put(std::uint8_t(1));
  out.put_array<float>(width);
  out.put_array<char>(merged);
  return out.take();
}

TileWidths widths_result(std::span<const std::byte> result, std::size_t own) {
  ByteReader in(result);
  TileWidths w;
  w.complete = in.get<std::uint8_t>() != 0;
  if (!w.complete) return w;
  w.h = in.get_array<float>();
  w.merged = in.get_array<char>();
  if (w.h.size() != own || w.merged.size() != own) throw Error("a tile's widths do not hold together");
  return w;
}

}  // namespace pss
