// The steps of `pss project` tile by tile that any process may work on (tiles/farm.hpp): each
// a request's bytes in, a result's bytes out, a pure function of the request, so that rank 0
// and the others give the same result for the same tile.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "pss/backend/backend.hpp"
#include "pss/points/orient_normals.hpp"
#include "pss/points/project_points.hpp"

namespace pss {

// A tile and its halo in the unit frame: the tile's own points first.
struct UnitTile {
  std::span<const vec3> unit;
  std::span<const float> h;      // each point's width
  std::span<const int> samples;  // the points kept as samples
  std::size_t own = 0;
};

// The outliers' distance (points/outliers.hpp) of each own sample of the tile.
std::vector<std::byte> outliers_request(const UnitTile& tile, float kappa);
std::vector<std::byte> work_outliers(std::span<const std::byte> request);
// Each own point's distance, NaN where it is no sample.
std::vector<float> outliers_result(std::span<const std::byte> result);

// The projection of each own point of the tile onto the MLS surface of its samples.
std::vector<std::byte> projection_request(const UnitTile& tile, float kappa, const ProjectionParams& unit_params,
                                          Backend backend);
std::vector<std::byte> work_projection(std::span<const std::byte> request);
struct TileProjections {
  std::vector<int> order;  // the own points in the grid's order, as they were projected
  std::vector<ProjectedPoint> projected;  // in that order
};
TileProjections projection_result(std::span<const std::byte> result);

// The orientation of a tile's projected points and its halo's (points/orient_normals.hpp:
// orient_normals_in_parts), in the unit frame.
std::vector<std::byte> orientation_request(std::span<const vec3> points, std::span<const vec3> normals,
                                           std::span<const float> radius, std::span<const std::uint64_t> id);
std::vector<std::byte> work_orientation(std::span<const std::byte> request);
struct TileOrientation {
  std::vector<vec3> normals;  // oriented
  OrientedParts parts;
};
TileOrientation orientation_result(std::span<const std::byte> result, std::size_t points);

}  // namespace pss
