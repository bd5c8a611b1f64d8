// A cloud file cut into cubic tiles on disk (issue 28): the first step of processing a
// cloud larger than memory, tile by tile, each with a halo of its neighbours' points. Two
// passes over the file (a PointStream): the first finds the count, the box and so the
// origin the whole-file readers choose (cloud.hpp), and whether every normal is usable; the
// second writes each point, with its input index and tidied normal, to its tile's bucket of
// a BucketFile. A tile's points then come back as the in-core cloud holds them: the same
// float positions about the same origin, the same normals.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <vector>

#include <glm/ext/vector_double3.hpp>

#include "pss/core/types.hpp"
#include "pss/io/bucket_file.hpp"
#include "pss/points/unit_frame.hpp"

namespace pss {

// The points of a tile and of its halo: the tile's own first (`own` of them), then the
// others, each group in input order.
struct TilePoints {
  std::vector<vec3> positions;
  std::vector<vec3> normals;  // empty when the cloud has none
  std::vector<std::uint64_t> index;
  std::size_t own = 0;
};

// How far p lies outside the box (0 within it): a halo holds the points within its width.
double distance_to_box(vec3 p, const Aabb& box);

class TiledCloud {
 public:
  // Reads `input` (.ply, .xyz, .las: open_point_stream) into tiles of about
  // `points_per_tile` points each where the points cover a surface, in a scratch file in
  // `folder`, buffering at most `buffer_bytes`.
  TiledCloud(const std::filesystem::path& input, const std::filesystem::path& folder, std::uint64_t points_per_tile,
             std::size_t buffer_bytes);

  std::uint64_t size() const { return points_; }
  glm::dvec3 origin() const { return origin_; }
  const Aabb& bounds() const { return bounds_; }  // of the positions about the origin
  // The in-core cloud's unit frame (points/unit_frame.hpp), from the same sample.
  UnitFrame unit_frame() const;
  bool has_normals() const { return normals_; }  // the file's, every one with a direction
  // The file's normals that have none (zero, not finite): where any do, has_normals is false
  // (in core, one makes all left out and estimated: points/sample_normals.hpp).
  std::uint64_t normals_without_direction() const { return normals_without_direction_; }
  bool has_colors() const { return colors_; }  // the file's (a tile does not carry them)
  int tiles() const { return int(counts_.x) * counts_.y * counts_.z; }
  std::uint64_t tile_size(int tile) const { return store_->records(tile); }
  Aabb tile_box(int tile) const;  // its cube of the box (its points lie within it)

  // The tile's points and, after them, every other point within `halo` of its box.
  TilePoints load(int tile, float halo) const;
  // The other tiles whose cubes lie within `reach` of the tile's, in their numbers' order.
  std::vector<int> tiles_near(int tile, float reach) const;
  // The tiles that hold points, in their numbers' order.
  std::vector<int> tiles_with_points() const;

  // The tile a point lies in, by its place in the grid of tiles: a point outside the box lies
  // in the nearest tile.
  int tile_of(vec3 p) const;
  ivec3 tile_cell_of(vec3 p) const;
  ivec3 tile_cell(int tile) const;  // its place in the grid of tiles

 private:

  std::uint64_t points_ = 0;
  glm::dvec3 origin_{0.0};
  Aabb bounds_;
  glm::dvec3 bulk_centre_{0.0};  // the unit frame's centre, about the origin
  bool normals_ = false;
  std::uint64_t normals_without_direction_ = 0;
  bool colors_ = false;
  float side_ = 1;
  ivec3 counts_{1};
  std::unique_ptr<BucketFile> store_;
};

}  // namespace pss
