// A point cloud on the host: positions and, when the file has them, unit normals, colours and
// other per-point scalar properties.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <glm/ext/vector_double3.hpp>
#include <glm/ext/vector_uint3_sized.hpp>

#include "pss/core/bulk_sample.hpp"
#include "pss/core/types.hpp"

namespace pss {

// 8 bits per channel, as the formats' colours nearly always are (PLY uchar, PCD packed rgb);
// wider or float colours are scaled to 0..255 by the readers.
using Rgb8 = glm::u8vec3;

// A scalar property's type as the file stores it (PLY's char, uchar, ... double).
enum class ScalarType { int8, uint8, int16, uint16, int32, uint32, float32, float64 };

// A per-point value beyond position, normal and colour (a scanner's intensity or confidence,
// a label): pss does not use it, but keeps it so that outputs can carry it through. A double
// holds a value of every ScalarType exactly.
struct ScalarProperty {
  std::string name;
  ScalarType type = ScalarType::float32;
  std::vector<double> values;  // one per position
};

// Positions are floats, as every kernel takes them, but floats keep about 7 digits: a
// georeferenced scan at 4·10⁶ m would be rounded to quarter-metre steps. So a cloud stores its
// positions as offsets from an origin that the readers choose in double (local_origin): the
// world position of point i is origin + positions[i], and outputs add the origin back.
struct PointCloud {
  glm::dvec3 origin{0.0};
  std::vector<vec3> positions;  // from origin
  std::vector<vec3> normals;            // empty, or one per position
  std::vector<Rgb8> colors;             // empty, or one per position
  std::vector<ScalarProperty> scalars;  // in the file's order
  // The points are a mesh's vertices (the file declares faces): its surface ends at its
  // boundary vertices, where a scan's ends somewhere past its last points (the ray tracer's
  // `--borders auto`, points/borders.hpp).
  bool mesh_vertices = false;

  std::size_t size() const { return positions.size(); }
  bool has_normals() const { return !normals.empty(); }
  bool has_colors() const { return !colors.empty(); }
  bool has_origin() const { return origin != glm::dvec3(0.0); }  // positions taken about one
  Aabb bounds() const {
    Aabb box;
    for (const vec3& p : positions) box.grow(p);
    return box;
  }
  glm::dvec3 world(std::size_t i) const { return origin + glm::dvec3(positions[i]); }
};

// The origin for world positions within [lo, hi], axis by axis: zero where floats already
// resolve the coordinates to within a few bits of what the cloud's size allows (within 4
// extents of zero; all of them when the positions are all equal), else the box's centre
// rounded to a multiple of a power of two at least the extent, so that a float coordinate
// minus the origin is exact (a float file reads back unchanged). The extent is the box's
// longest side: a scan whose box spans 4·10⁶ m (a stray point at zero) keeps a float's
// steps at that scale.
glm::dvec3 local_origin(const glm::dvec3& lo, const glm::dvec3& hi);
// The same about a given centre (rounded as above).
glm::dvec3 local_origin(const glm::dvec3& lo, const glm::dvec3& hi, const glm::dvec3& centre);
// The origin the readers choose for world positions within [lo, hi] of which `sample` kept
// some: local_origin of [lo, hi], unless that box is the strays' (BulkSample::box_of_strays):
// then of the bulk (its 2–98 % box, about its median), so that a few points far from the rest
// do not take the floats' precision from it.
glm::dvec3 bulk_origin(const BulkSample& sample, const glm::dvec3& lo, const glm::dvec3& hi);

// Sets the cloud's origin and its positions from world positions, finite and within float's
// range (the readers refuse others, naming the point).
void set_world_positions(PointCloud& cloud, const std::vector<glm::dvec3>& world);
// The same for positions that floats hold exactly (a file of floats), offset in place: the
// same positions, at half the memory (issue 28). The origin is a multiple of a power of two
// at least the extent, so a float minus it rounds as its double does.
void set_world_positions(PointCloud& cloud, std::vector<vec3>&& world);

}  // namespace pss
