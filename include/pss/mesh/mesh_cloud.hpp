// The mesh of a cloud's PSS (`pss mesh`, issue 27): marching tetrahedra
// (mesh/marching_tetrahedra.hpp) over the cubes near the samples, of the PSS's signed
// distance (mesh/cloud_implicit.hpp), every vertex a root of it on its edge, with the PSS's
// normal there. Any surface operator and support of `pss project`.
#pragma once

#include <cstdint>
#include <functional>
#include <span>

#include "pss/backend/backend.hpp"
#include "pss/core/stats.hpp"
#include "pss/mesh/marching_tetrahedra.hpp"
#include "pss/points/cloud.hpp"
#include "pss/points/outliers.hpp"
#include "pss/points/projection.hpp"
#include "pss/points/sample_normals.hpp"
#include "pss/points/support.hpp"
#include "pss/points/unit_frame.hpp"

namespace pss {

// The cube's side at h (or the least h_i): about the samples' spacing (h is their distance
// to the 15th neighbour, about 2.2 spacings on a surface), so that the mesh resolves what
// the PSS resolves, at a few triangles per sample.
inline constexpr float kDefaultCellPerH = 0.5f;

// Normals within a cube differing by more than this many degrees may mark a sharp crease
// (marching_tetrahedra.hpp): a box's edges (90°) and a blade's trailing edge. A smooth
// surface turns this far within a cube only where its radius of curvature is below about
// 3 cubes, and there its tangent planes meet off the surface (src/mesh/creases.hpp).
inline constexpr float kDefaultCreaseAngle = 30.0f;

struct MeshParams {
  ProjectionParams projection;  // its borders: clip ends the mesh where the samples end
  float cell = 0;               // the cubes' side; 0: kDefaultCellPerH·h
  float crease_angle = kDefaultCreaseAngle;  // degrees, in (0, 180]; 180: no creases
};

// A part of a cloud's mesh (vertices joined by triangles) is held by the samples within its
// bounding sphere; one held by fewer than this, as few as a fit takes (points/projection.hpp),
// is no surface of the data's: the bubble the fits wrap around a noisy sample a few σ off
// the surface (a 30,000-point sphere with noise 0.4 h gave 48 of them), and is removed.
inline constexpr int kMinPartSamples = 3;

struct CloudMesh {
  TriangleMesh mesh;
  MarchCounts counts;
  float cell = 0;
  SupportWidths widths;  // least, median, largest h_i (h is not kept)
  NormalsUsed normals = NormalsUsed::none;  // the samples' oriented normals: the file's or estimated
  std::size_t normals_turned = 0;
  std::size_t file_normals_off = 0;  // the file's off their neighbours' planes, where all were left out
  OutlierReport outliers;
  // Whether the normals' orientation, a guess (estimated: orient_normals.hpp; or the file's
  // with some turned), enclosed a negative volume, and the mesh was turned to face out.
  bool turned_outward = false;
};

// Where the samples' normals were estimated, or the file's contradicted each other (some
// turned), the mesh faces out: its closed components enclose a positive volume. The file's
// normals that agree are taken as they say.
// Throws Error for invalid parameters (as project_cloud), a cell that is not a positive
// number or too small for the cloud's extent or surface (band_cube_limit), a cloud of
// fewer than three points or on a line, and a cloud that gives no triangle.
CloudMesh mesh_cloud(const PointCloud& cloud, const MeshParams& params, Backend backend, Stats& stats);

// What mesh_cloud and its tiles (tiles/mesh.hpp) share:
// The cubes' side; throws Error for invalid parameters, as mesh_cloud.
float mesh_cell(const MeshParams& params);
// The cubes of the band, about: one per cell² of surface, each sample's width h_i standing for
// about h_i² of it (h_i is its distance to the 15th neighbour: about 2.2 spacings);
// Σ (h_i/cell)² overestimates them about 3-fold (the bunny: 144,000 for 42,000).
double expected_band_cubes(std::span<const float> widths, double cell);
// The lattice in `frame` (unit: `widest_rho`, the samples' widest support ρ_i, and `cell`)
// over the cloud's box `box`, past it as far as the surface may reach (with extended
// borders, the widest ρ_i and a cube; at least two cubes), its planes half a cube off the box's faces:
// a flat face on the box (a CAD part's base) would lie on a plane of corners, where f is 0
// give or take its rounding, and the march found no cube it crossed. `cell_given`: --cell,
// which an error then names (else h/2).
Lattice cloud_lattice(const Aabb& box, const UnitFrame& frame, BorderMode borders, double widest_rho, double cell,
                      bool cell_given);

// Adds to inside[p] the samples within radius[p] of centre[p], for each p.
using CountSamples =
    std::function<void(std::span<const vec3> centre, std::span<const float> radius, std::span<int> inside)>;
// Removes every part (vertices joined by triangles) whose bounding sphere, about its
// vertices' mean, holds fewer than kMinPartSamples samples as `count` counts them, and the
// vertices left unused. Returns the number of parts removed.
std::int64_t remove_unsupported_parts(TriangleMesh& mesh, const CountSamples& count);

// Where out.normals were a guess, turns the mesh to face out as mesh_cloud says, and each
// closed part by its depth; throws Error where the mesh has no triangle.
void finish_cloud_mesh(CloudMesh& out, const ProjectionParams& projection);

}  // namespace pss
