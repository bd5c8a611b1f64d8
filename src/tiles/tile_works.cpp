#include "tile_works.hpp"

#include <limits>

#include "pss/backend/cpu/parallel_for.hpp"
#include "pss/backend/mirror.hpp"
#include "pss/backend/parallel_for.hpp"
#include "pss/core/stats.hpp"
#include "pss/points/outliers.hpp"
#include "pss/spatial/grid_mirror.hpp"
#include "pss/spatial/support_grid.hpp"
#include "tile_bytes.hpp"

namespace pss {

namespace {

void put_tile(ByteWriter& out, const UnitTile& tile, float kappa) {
  out.put(kappa);
  out.put(std::uint64_t(tile.own));
  out.put_array(tile.unit);
  out.put_array(tile.h);
  out.put_array(tile.samples);
}

struct TileArrays {
  float kappa;
  std::size_t own;
  std::vector<vec3> unit;
  std::vector<float> h;
  std::vector<int> samples;
};

TileArrays get_tile(ByteReader& in) {
  TileArrays t{in.get<float>(), std::size_t(in.get<std::uint64_t>()), in.get_array<vec3>(), in.get_array<float>(),
               in.get_array<int>()};
  if (t.h.size() != t.unit.size() || t.own > t.unit.size()) throw Error("a tile's work does not hold together");
  for (const int s : t.samples)
    if (s < 0 || std::size_t(s) >= t.unit.size()) throw Error("a tile's work does not hold together");
  return t;
}

}  // namespace

std::vector<std::byte> outliers_request(const UnitTile& tile, float kappa) {
  ByteWriter out;
  put_tile(out, tile, kappa);
  return out.take();
}

// On the CPU, over the tile's own samples only (a GPU launch would measure the halo's too,
// whose kernel runs over every sample of a grid).
std::vector<std::byte> work_outliers(std::span<const std::byte> request) {
  ByteReader in(request);
  const TileArrays t = get_tile(in);
  const SupportGrid grid(t.unit, t.h, t.samples, t.kappa);
  const std::span<const int> original = grid.original_index();
  std::vector<int> own;  // the tile's own samples, by sorted index
  for (std::size_t k = 0; k < original.size(); ++k)
    if (std::size_t(original[k]) < t.own) own.push_back(int(k));
  std::vector<float> out(original.size());
  const OutlierDistanceKernel kernel{grid.view(), out.data()};
  cpu::parallel_for(std::int64_t(own.size()), [&](std::int64_t m) { kernel(own[std::size_t(m)]); });
  std::vector<float> distance(t.own, std::numeric_limits<float>::quiet_NaN());
  for (const int k : own) distance[std::size_t(original[std::size_t(k)])] = out[std::size_t(k)];
  ByteWriter result;
  result.put_array<float>(distance);
  return result.take();
}

std::vector<float> outliers_result(std::span<const std::byte> result) {
  ByteReader in(result);
  return in.get_array<float>();
}

std::vector<std::byte> projection_request(const UnitTile& tile, float kappa, const ProjectionParams& unit_params,
                                          Backend backend) {
  ByteWriter out;
  put_tile(out, tile, kappa);
  out.put(unit_params);
  out.put(backend);
  return out.take();
}

// MLS gathers N(r) once, at the point (points/surface_projection.hpp): the halo holds it.
std::vector<std::byte> work_projection(std::span<const std::byte> request) {
  ByteReader in(request);
  const TileArrays t = get_tile(in);
  const auto params = in.get<ProjectionParams>();
  const auto backend = in.get<Backend>();
  const SupportGrid grid(t.unit, t.h, t.samples, t.kappa);
  const GridMirror g(backend, grid);
  // The own points in the grid's order, then those set aside: neighbouring threads gather
  // neighbouring samples, as in core (a file's random order costs a fifth).
  std::vector<int> order;
  order.reserve(t.own);
  std::vector<char> placed(t.own, 0);
  for (const int i : grid.original_index())
    if (std::size_t(i) < t.own) {
      order.push_back(i);
      placed[std::size_t(i)] = 1;
    }
  for (std::size_t i = 0; i < t.own; ++i)
    if (!placed[i]) order.push_back(int(i));
  std::vector<vec3> own_points(t.own);
  for (std::size_t k = 0; k < t.own; ++k) own_points[k] = t.unit[std::size_t(order[k])];
  const Mirror<vec3> points(backend, own_points);
  Mirror<ProjectedPoint> out(backend, t.own);
  Stats stats;  // the caller times and shows the step whole
  parallel_for(backend, "projection", std::int64_t(t.own),
               ProjectPointsKernel{g.view(), points.data(), nullptr, out.data(), params}, stats, nullptr, false);
  const std::vector<ProjectedPoint> done = out.take();
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

std::vector<std::byte> orientation_request(std::span<const vec3> points, std::span<const vec3> normals,
                                           std::span<const float> radius, std::span<const std::uint64_t> id) {
  ByteWriter out;
  out.put_array(points);
  out.put_array(normals);
  out.put_array(radius);
  out.put_array(id);
  return out.take();
}

std::vector<std::byte> work_orientation(std::span<const std::byte> request) {
  ByteReader in(request);
  const auto points = in.get_array<vec3>();
  auto normals = in.get_array<vec3>();
  const auto radius = in.get_array<float>();
  const auto id = in.get_array<std::uint64_t>();
  if (normals.size() != points.size() || radius.size() != points.size() || id.size() != points.size())
    throw Error("a tile's work does not hold together");
  const OrientedParts parts = orient_normals_in_parts(points, normals, radius, id);
  ByteWriter result;
  result.put_array<vec3>(normals);
  result.put_array<int>(parts.of_point);
  result.put_array<int>(parts.root);
  return result.take();
}

TileOrientation orientation_result(std::span<const std::byte> result, std::size_t points) {
  ByteReader in(result);
  TileOrientation o{in.get_array<vec3>(), {in.get_array<int>(), in.get_array<int>()}};
  bool whole = o.normals.size() == points && o.parts.of_point.size() == points;
  for (const int part : o.parts.of_point) whole = whole && part >= 0 && std::size_t(part) < o.parts.root.size();
  for (const int root : o.parts.root) whole = whole && root >= 0 && std::size_t(root) < points;
  if (!whole) throw Error("a tile's orientation does not hold together");
  return o;
}

}  // namespace pss
