#include "pss/io/tiled_cloud.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

#include "pss/core/error.hpp"
#include "pss/core/progress.hpp"
#include "pss/io/point_cloud_file.hpp"
#include "pss/io/point_stream.hpp"
#include "pss/points/cloud.hpp"

namespace pss {

namespace {

constexpr std::size_t kPart = std::size_t(1) << 16;
constexpr int kMostTiles = 1 << 16;  // a bucket costs some words of memory and a buffer

struct Record {  // a point as its tile holds it
  std::uint64_t index;
  vec3 position, normal;
};
static_assert(sizeof(Record) == 32);

}  // namespace

// In double: a float's square overflows past ~1.8e19, and a halo point 1e30 away would
// read as infinitely far.
UnitFrame TiledCloud::unit_frame() const {
  return unit_frame_about(glm::dvec3(bounds_.lo), glm::dvec3(bounds_.hi), bulk_centre_);
}

double distance_to_box(vec3 p, const Aabb& box) {
  return glm::length(glm::max(glm::max(glm::dvec3(box.lo) - glm::dvec3(p), glm::dvec3(p) - glm::dvec3(box.hi)), glm::dvec3(0.0)));
}

TiledCloud::TiledCloud(const std::filesystem::path& input, const std::filesystem::path& folder,
                       std::uint64_t points_per_tile, std::size_t buffer_bytes) {
  // Pass 1: the count, the box, whether the normals are usable: every one with a direction
  // (in core, one without makes all left out and estimated: sample_normals.hpp).
  glm::dvec3 lo(0.0), hi(0.0);
  BulkSample sample;  // the in-core reader's (cloud.hpp: bulk_origin)
  bool any_normals = false;
  {
    const auto stream = open_point_stream(input);
    // A text file declares no count: its first reading shows none.
    std::optional<Progress> progress;
    if (stream->declared_count() > 0) progress.emplace("reading (the box)", std::int64_t(stream->declared_count()));
    PointPart part;
    while (stream->read(part, kPart) > 0) {
      if (progress) progress->advance(std::int64_t(part.size()));
      for (const glm::dvec3& w : part.world) {
        if (points_ == 0) lo = hi = w;
        lo = glm::min(lo, w);
        hi = glm::max(hi, w);
        sample.add(w);
        ++points_;
      }
      any_normals = any_normals || !part.normals.empty();
      colors_ = colors_ || !part.colors.empty();
      for (const vec3& n : part.normals) normals_without_direction_ += !(is_finite(n) && n != vec3(0.0f));
      part.clear();
    }
  }
  origin_ = bulk_origin(sample, lo, hi);

  normals_ = any_normals && normals_without_direction_ == 0;
  // Rounding to float keeps order: the box of the rounded positions is the rounded box.
  bounds_.lo = vec3(lo - origin_);
  bounds_.hi = vec3(hi - origin_);
  {  // the unit frame's centre, from the positions the in-core cloud holds (its floats)
    std::vector<glm::dvec3> kept;
    for (const glm::dvec3& w : sample.kept()) kept.emplace_back(vec3(w - origin_));
    bulk_centre_ = frame_centre(std::move(kept), glm::dvec3(bounds_.lo), glm::dvec3(bounds_.hi));
  }
  // Tiles as wide as a surface across the box's longest side needs for points_per_tile
  // points a tile (a surface's points grow with its area, the square of the side).
  const vec3 extent = bounds_.extent();
  const float longest = std::max({extent.x, extent.y, extent.z});
  double across = std::max(1.0, std::ceil(std::sqrt(double(points_) / double(std::max<std::uint64_t>(points_per_tile, 1)))));
  for (;; across = std::max(1.0, std::floor(across * 0.8))) {
    side_ = longest > 0 ? float(double(longest) / across) : 1.0f;
    counts_ = glm::max(ivec3(glm::ceil(extent / side_)), ivec3(1));
    if (std::int64_t(counts_.x) * counts_.y * counts_.z <= kMostTiles || across == 1) break;
  }
  store_ = std::make_unique<BucketFile>(folder, tiles(), sizeof(Record), buffer_bytes);

  // Pass 2: each point to its tile, as the in-core cloud would hold it.
  const auto stream = open_point_stream(input);
  Progress progress("reading into tiles", std::int64_t(points_));
  PointPart part;
  std::uint64_t index = 0;
  while (stream->read(part, kPart) > 0) {
    progress.advance(std::int64_t(part.size()));
    for (std::size_t k = 0; k < part.size(); ++k, ++index) {
      Record r{index, vec3(part.world[k] - origin_), vec3(0.0f)};
      if (normals_) r.normal = tidy_normal(part.normals[k]);
      if (index >= points_ || !is_finite(r.position))
        throw file_error(input, "changed while it was read: its points differ between two readings");
      store_->append(tile_of(r.position), &r);
    }
    part.clear();
  }
  if (index != points_) throw file_error(input, "changed while it was read: its points differ between two readings");
  store_->flush();
}

// In double, where a float's difference is exact: a point's tile and the tile's box agree.
ivec3 TiledCloud::tile_cell_of(vec3 p) const {
  const glm::dvec3 at = glm::floor((glm::dvec3(p) - glm::dvec3(bounds_.lo)) / double(side_));
  return glm::clamp(ivec3(glm::clamp(at, glm::dvec3(-1.0), glm::dvec3(counts_))), ivec3(0), counts_ - 1);
}

int TiledCloud::tile_of(vec3 p) const {
  const ivec3 c = tile_cell_of(p);
  return (c.z * counts_.y + c.y) * counts_.x + c.x;
}

ivec3 TiledCloud::tile_cell(int tile) const {
  return ivec3(tile % counts_.x, tile / counts_.x % counts_.y, tile / counts_.x / counts_.y);
}

Aabb TiledCloud::tile_box(int tile) const {
  const ivec3 c = tile_cell(tile);
  const glm::dvec3 lo = glm::dvec3(bounds_.lo) + glm::dvec3(c) * double(side_), hi = lo + double(side_);
  Aabb box;  // its float bounds a step outward: every point of the tile lies within them
  for (int k = 0; k < 3; ++k) {
    box.lo[k] = std::nextafter(float(lo[k]), -kInfinity);
    box.hi[k] = std::nextafter(float(hi[k]), kInfinity);
  }
  return box;
}

TilePoints TiledCloud::load(int tile, float halo) const {
  TilePoints out;
  auto add = [&](const Record& r) {
    out.positions.push_back(r.position);
    if (normals_) out.normals.push_back(r.normal);
    out.index.push_back(r.index);
  };
  std::vector<Record> near;  // the halo's points, put in input order below
  const Aabb box = tile_box(tile);
  auto take = [&](int from, bool own) {
    store_->for_each_record<Record>(from, [&](const Record& r) {
      if (own) add(r);
      else if (distance_to_box(r.position, box) <= double(halo)) near.push_back(r);
    });
  };
  take(tile, true);
  out.own = out.positions.size();
  for (const int other : tiles_near(tile, halo)) take(other, false);
  std::sort(near.begin(), near.end(), [](const Record& a, const Record& b) { return a.index < b.index; });
  for (const Record& r : near) add(r);
  return out;
}

std::vector<int> TiledCloud::tiles_with_points() const {
  std::vector<int> with;
  for (int t = 0; t < tiles(); ++t)
    if (tile_size(t) > 0) with.push_back(t);
  return with;
}

std::vector<int> TiledCloud::tiles_near(int tile, float reach) const {
  const ivec3 c = tile_cell(tile);
  // Rings of neighbours as wide as the reach, at most the whole grid (a reach of 10^30 is no
  // integer's worth of tiles).
  const int rings = int(std::min(std::ceil(double(reach) / side_), double(std::max({counts_.x, counts_.y, counts_.z}))));
  std::vector<int> near;
  for (int z = std::max(0, c.z - rings); z <= std::min(counts_.z - 1, c.z + rings); ++z)
    for (int y = std::max(0, c.y - rings); y <= std::min(counts_.y - 1, c.y + rings); ++y)
      for (int x = std::max(0, c.x - rings); x <= std::min(counts_.x - 1, c.x + rings); ++x) {
        const int other = (z * counts_.y + y) * counts_.x + x;
        if (other != tile) near.push_back(other);
      }
  return near;
}

}  // namespace pss
