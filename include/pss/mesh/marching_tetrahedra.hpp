// Marching tetrahedra over a narrow band of lattice cubes (issue 27): the cubes are found by
// following the surface from seeds, never by sweeping a grid, so that time and memory grow
// with the surface's area, not its box's volume. Each cube splits into the six tetrahedra
// of its main diagonal (Kuhn's split, the same in every cube, so neighbours share their
// faces' diagonals); a tetrahedron whose corners' signs differ holds one triangle or two.
// The triangles of such a split are an embedded surface wherever each vertex lies on its
// edge, strictly between the corners: every vertex is a root of the implicit on its edge
// (ImplicitSurface::cross), so the mesh lies on the surface with no self-intersection.
// Why tetrahedra, not marching cubes' table: docs/architecture.md.
#pragma once

#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include <glm/ext/vector_double3.hpp>

#include "pss/core/progress.hpp"
#include "pss/mesh/implicit.hpp"
#include "pss/mesh/triangle_mesh.hpp"

namespace pss {

// Cubes of side `cell` from `origin`, corner (i, j, k) at origin + cell·(i, j, k), at most
// 2^20 corners along each axis (lattice_over throws a one-line Error beyond).
struct Lattice {
  static constexpr int kBits = 20;
  glm::dvec3 origin{0.0};
  double cell = 1;
  ivec3 size{0};  // corners along each axis

  vec3 position(ivec3 c) const { return vec3(origin + cell * glm::dvec3(c)); }
  ivec3 cube_of(vec3 p) const;  // the cube holding p (may lie outside)
  bool holds_cube(ivec3 c) const {
    return c.x >= 0 && c.y >= 0 && c.z >= 0 && c.x + 1 < size.x && c.y + 1 < size.y && c.z + 1 < size.z;
  }
  static std::uint64_t key(ivec3 c) {
    return (std::uint64_t(c.x) << (2 * kBits)) | (std::uint64_t(c.y) << kBits) | std::uint64_t(c.z);
  }
  static ivec3 corner(std::uint64_t key) {
    const std::uint64_t mask = (1u << kBits) - 1;
    return ivec3(int(key >> (2 * kBits)), int((key >> kBits) & mask), int(key & mask));
  }
};

// A band's cost: the whole run's peak over the cubes the band's estimate gives (mesh_cloud,
// mesh_volume), measured on 2026-11-28: 650-740 bytes on noisy tori of 10^6 and 10^7 points
// (their clouds included), about 950 on the engine CT (the band's own share, its cubes
// crossed by six triangles each).
inline constexpr double kBandBytesPerCube = 1024;
// Where the machine's memory is unknown: 2^23 cubes, some 8 GiB.
inline constexpr std::int64_t kBandCubesWithoutMemory = std::int64_t(1) << 23;

// The most cubes a mesh's band may hold where the process may take `memory` bytes: those
// that three quarters of it hold at kBandBytesPerCube (the rest for the data and the
// system); kBandCubesWithoutMemory where `memory` is unknown (not positive).
std::int64_t band_cube_limit(std::int64_t memory);

// A band's corners per cube it meshes (the dragon: 54,171 for 26,048; the bunny at a
// quarter of its default cell: 1,046,959 for 518,746): the progress's estimate from the
// band's cubes.
inline constexpr double kCornersPerBandCube = 2;

// Throws a one-line Error when `expected_cubes`, a mesh's estimate of its band at the cell
// size `cell`, exceeds band_cube_limit of this process's memory (core/memory.hpp), before
// any work; `data` names what is meshed ("cloud", "volume").
void check_band(double expected_cubes, double cell, const char* data);

// The lattice over the box [lo, hi] grown by `margin` on every side; `what` names the
// cell size in the error where the box holds too many cells ("--cell"), its lengths
// multiplied by `shown_scale` (a lattice in a cloud's unit frame names the data's).
Lattice lattice_over(vec3 lo, vec3 hi, double margin, double cell, const char* what, double shown_scale = 1.0);

struct MarchCounts {
  std::int64_t corners = 0;          // corners evaluated
  std::int64_t cubes_visited = 0;
  std::int64_t cubes_crossed = 0;    // with triangles
  std::int64_t cubes_refused = 0;    // signs differ, but a corner invalid or a jump between two
  std::int64_t crease_vertices = 0;    // on sharp creases (src/mesh/creases.hpp)
  std::int64_t crease_flips = 0;       // edges turned to join two of them
  std::int64_t pinched_triangles = 0;  // removed to keep every vertex one fan (remove_pinches)
  std::int64_t normals_turned = 0;     // facing against their triangles (normals_follow_winding)
  std::int64_t collapsed_vertices = 0;  // removed by coarsen_mesh (mesh_cloud.cpp, mesh_volume.cpp)
  std::int64_t unsupported_parts = 0;  // a cloud's mesh: parts no samples hold, removed (mesh_cloud.cpp)
  std::int64_t closed_parts_turned = 0;  // a cloud's mesh of a guessed side: face_closed_parts_outward
};

// The mesh of the implicit's zero set in the cubes reached from the cubes holding `seeds`:
// a cube is meshed when its eight corners are valid, their signs differ, and of any two
// corners of opposite signs the nearer to the surface lies within `max_slope` times their
// distance of it (where the surface passes between two points, a distance to it is at most
// theirs at either end; where both are farther, the sign changes across a jump of the
// implicit, not the surface, unless the data put both on their sides); the band grows into the face neighbours across faces whose
// corners' signs differ and into the cubes of the corners' surface points. The result is
// edge-manifold, vertex-manifold, consistently oriented (outward: towards positive
// distance) and deterministic: the same for any thread count and batch order. Where the
// normals within a cube differ by more than `crease_angle` degrees (180: nowhere) and the
// surface has a crease there, the cube's vertex on it replaces the chamfer (creases.hpp).
// Each vertex's normal is the surface's at it, turned where it faces against its triangles
// (at a fold or a thin part's rim the fit's normal may follow the other sheet).
// `expected_corners`, the caller's estimate of the band's corners (0: none), is the progress's
// total from the start: the first wave alone was a quarter of the bunny's at a fine cell, and
// its "90 %" came with most of the time to go.
TriangleMesh march_tetrahedra(const Lattice& lattice, std::span<const vec3> seeds, const ImplicitSurface& implicit,
                              float max_slope, float crease_angle, MarchCounts& counts,
                              std::int64_t expected_corners = 0);

// The cubes lo <= c < hi, axis by axis.
struct CubeBox {
  ivec3 lo{0}, hi{0};
  bool holds(ivec3 c) const {
    return c.x >= lo.x && c.y >= lo.y && c.z >= lo.z && c.x < hi.x && c.y < hi.y && c.z < hi.z;
  }
};

// A piece of a march (`pss mesh` tile by tile, issue 28), keyed for welding to its
// neighbours: each vertex's key (an edge's root: the edge's lower corner's Lattice::key << 3 |
// its direction, 1..7; a crease's fan centre: its cube's key << 3) and each triangle's cube
// and place among the cube's triangles. Its pinches are not removed and its normals not yet
// turned to follow the winding: both look past the piece (MeshWelder, mesh/weld.hpp).
struct MarchedPiece {
  TriangleMesh mesh;
  std::vector<std::uint64_t> vertex_key;
  std::vector<std::uint64_t> triangle_cube;
  std::vector<std::int32_t> triangle_place;
};

// march_tetrahedra's march over the cubes of `marched` only, keeping the triangles of the
// cubes of `kept` (within `marched`), and their vertices. Where `marched` reaches a few cubes
// past `kept` on every side, pieces of neighbouring `kept` boxes agree where they meet: the
// same vertices on the same edges, the same crease fans.
MarchedPiece march_piece(const Lattice& lattice, std::span<const vec3> seeds, const ImplicitSurface& implicit,
                         float max_slope, float crease_angle, const CubeBox& marched, const CubeBox& kept,
                         MarchCounts& counts);

// Removes the triangles of every fan but the largest at each vertex where a mesh's
// triangles meet in more than one fan (touching at a vertex only), until none does; then
// the vertices no triangle uses (dropped from `follow` too, one value a vertex, where given).
// Returns how many triangles it removed.
std::int64_t remove_pinches(TriangleMesh& mesh, std::vector<float>* follow = nullptr);

}  // namespace pss
