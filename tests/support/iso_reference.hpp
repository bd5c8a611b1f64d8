// The real-data reference for `pss volume --iso v` (docs: ANCHORS "Real data"): the field's
// standard surface, exactly where the trilinear interpolant of the voxels crosses v, none
// elsewhere and none on the volume's boundary (VTK Flying Edges / marching cubes).
// Two independent forms of it, both built only from the voxels:
// - cast_iso_reference: per pixel, the first crossing along the same primary ray pss casts
//   (3-D DDA through the cells, fine sampling and bisection inside cells that straddle v);
// - ReferenceMesh: the marching-tetrahedra triangles of the same surface, with the exact
//   distance of any point to them through a uniform grid.
// compare_to_reference scores pss's hits against both; measure_against_reference, at the
// bottom, is the one place that calls pss's volume method, so that a real-data test or the
// bench (bench/volume_vs_reference.cpp) is a few lines.
#pragma once

#include <cstdint>
#include <vector>

#include "pss/render/camera.hpp"
#include "pss/core/hit.hpp"
#include "pss/volume/volume.hpp"
#include "support/marching_tetrahedra.hpp"

namespace pss {
struct PreparedVolume;
struct RenderedFrame;
}  // namespace pss

namespace pss::test {

struct ReferencePixel {
  bool found = false;
  float t = kInfinity;  // along the primary ray (unit direction)
  vec3 point{0.0f};
  vec3 normal{0.0f};    // unit, along the gradient (toward higher values)
};

struct ReferenceImage {
  int width = 0, height = 0;
  std::vector<ReferencePixel> pixels;  // row-major from the top row, as RenderedFrame::hits
};

// The first crossing of `iso` by the trilinear interpolant along `ray`, inside the box of
// the voxel centres. Cells are walked in order (Amanatides–Woo); in a cell whose corners
// straddle iso (min ≤ iso < max: "above" is value > iso) the interpolant is sampled every 1/`steps_per_voxel` voxel of ray length and the first sign change is
// bisected. Two crossings closer than one step can be missed: a fold thinner than 1/16
// voxel. Where the ray enters the box already above iso, the box face is not a surface.
// The normal is the central-difference gradient interpolated trilinearly (as VTK's).
ReferencePixel cast_iso_ray(const VolumeView& v, float iso, const Ray& ray, int steps_per_voxel = 16);

// cast_iso_ray for every pixel's Camera::primary_ray, in parallel.
ReferenceImage cast_iso_reference(const VolumeView& v, float iso, const Camera& camera, int steps_per_voxel = 16);

// Exact point–triangle distance (Ericson, Real-Time Collision Detection §5.1.5).
float point_triangle_distance(vec3 p, const Triangle& t);

// The marching-tetrahedra triangles of the iso-surface, and distances to them through a
// uniform grid of cells (each triangle listed in every cell its box overlaps).
class ReferenceMesh {
 public:
  ReferenceMesh() = default;
  ReferenceMesh(const VolumeView& v, float iso);
  ReferenceMesh(std::vector<Triangle> triangles, float cell_size);

  const std::vector<Triangle>& triangles() const { return triangles_; }
  // Distance to the nearest triangle (kInfinity without triangles): the cells around p,
  // ring by ring, until the best distance is within the inner radius of the next ring.
  float distance(vec3 p) const;
  // Over all triangles: what distance() is tested against.
  float distance_brute_force(vec3 p) const;

 private:
  std::vector<Triangle> triangles_;
  vec3 lo_{0.0f};
  float cell_ = 1;
  ivec3 cells_{0};
  std::vector<std::int64_t> start_;  // CSR: triangles of cell c are items_[start_[c], start_[c+1])
  std::vector<std::int32_t> items_;
};

struct ReferenceComparison {
  std::int64_t object_pixels = 0;   // the reference hits
  std::int64_t hole_pixels = 0;     // the reference hits, pss does not
  std::int64_t phantom_pixels = 0;  // pss hits, the reference does not
  std::int64_t pss_hits = 0;
  double holes = 0, phantom = 0;  // fractions of object_pixels
  // The same away from the silhouette's rim: holes whose 8 neighbours the reference all
  // hits, phantom pixels none of whose 8 neighbours it hits. A PSS smooths at the scale h
  // and may move a silhouette by a fraction of a voxel, a pixel or so at these sizes; what
  // remains is surface missing or made up.
  std::int64_t interior_hole_pixels = 0, exterior_phantom_pixels = 0;
  double interior_holes = 0, exterior_phantom = 0;
  // Of every pss hit point to the mesh, in voxels.
  double mean_distance = 0, p99_distance = 0, max_distance = 0;
  // Of the pixels both hit: those where pss's point is more than one voxel in front of the
  // reference's (a phantom surface hiding the real one) or behind it (a hole in the first
  // surface, through to one behind), as fractions of object_pixels; the mean distance
  // from pss's point to the reference's, in voxels; and the mean angle between the normals
  // (|cos|: either orientation), degrees.
  std::int64_t in_front_pixels = 0, behind_pixels = 0;
  double in_front = 0, behind = 0;
  double mean_depth_difference = 0;
  double mean_normal_angle_deg = 0;
};

// pss's per-pixel hits (RenderedFrame::hits) against the reference of the same camera.
ReferenceComparison compare_to_reference(const std::vector<Hit>& hits, const ReferenceImage& ref,
                                         const ReferenceMesh& mesh, float voxel);

// Grey headlight-diffuse image of the reference (background black), for a person to look at.
std::vector<vec3> shade_reference(const ReferenceImage& ref, const Camera& camera);

// Where pss and the reference disagree, over the reference's grey image: red where pss
// has a surface the reference has not (phantom, or in front by more than a voxel), blue
// where it misses the reference's (hole, or behind by more than a voxel).
std::vector<vec3> disagreement_image(const std::vector<Hit>& hits, const ReferenceImage& ref, const Camera& camera,
                                     float voxel);

// --- The one place that calls pss's volume method. ---

// The camera of `pss volume` with the default render options, WxH, orbited to the view,
// framing `box` (pss volume frames PreparedVolume::surface_bounds()).
Camera volume_camera(const Aabb& box, int width, int height, float azimuth_deg, float elevation_deg);

// pss's frame of a prepared volume on the CPU, with the default render settings.
// `frame_seconds` gets the time of its primary rays and shading.
RenderedFrame render_pss(const PreparedVolume& volume, const Camera& camera, double* frame_seconds = nullptr);

struct ReferenceMeasurement {
  ReferenceComparison comparison;
  ReferenceImage reference;
  std::vector<Hit> hits;
  std::vector<vec3> pss_image;  // linear RGB, as rendered
  double pss_seconds = 0, reference_seconds = 0;
};

// Render `volume` (prepared for iso) through `camera` and score it against the reference
// of the same volume's voxels; `mesh` must be ReferenceMesh(volume's view, iso).
ReferenceMeasurement measure_against_reference(const PreparedVolume& volume, float iso, const Camera& camera,
                                               const ReferenceMesh& mesh);

}  // namespace pss::test
