// `pss mesh` tile by tile: a tile's piece of the mesh (tile_works.hpp).
#include "pss/core/error.hpp"
#include "pss/core/progress.hpp"
#include "tile_arrays.hpp"
#include "tile_works.hpp"

namespace pss {

namespace {

// A tile's march shows no progress of its own (the caller's counts the tiles): where the
// tile is worked on in this process, its bars would interleave with the caller's.
class QuietProgress {
 public:
  QuietProgress() : mode_(progress_mode()) { set_progress_mode(ProgressMode::never); }
  ~QuietProgress() { set_progress_mode(mode_); }
  QuietProgress(const QuietProgress&) = delete;
  QuietProgress& operator=(const QuietProgress&) = delete;

 private:
  ProgressMode mode_;
};

bool inside(const CubeBox& box, const Lattice& lattice) {
  return box.lo.x >= 0 && box.lo.y >= 0 && box.lo.z >= 0 && box.hi.x <= lattice.size.x &&
         box.hi.y <= lattice.size.y && box.hi.z <= lattice.size.z;
}

}  // namespace

std::vector<std::byte> mesh_request(const UnitTile& tile, const ProjectionParams& unit_params,
                                    const MeshPieceInputs& inputs, Backend backend) {
  ByteWriter out;
  put_tile(out, tile);
  out.put(unit_params);
  out.put(inputs);
  out.put(backend);
  return out.take();
}

std::vector<std::byte> work_mesh(std::span<const std::byte> request) {
  ByteReader in(request);
  const TileArrays t = get_tile(in);
  const auto params = in.get<ProjectionParams>();
  const auto inputs = in.get<MeshPieceInputs>();
  const auto backend = in.get<Backend>();
  const Lattice& lattice = inputs.lattice;
  if (t.normals.size() != t.unit.size() || !(lattice.cell > 0) || !inside(inputs.kept, lattice))
    throw Error("a tile's work does not hold together: a mesh needs the samples' normals and a box in its lattice");
  CloudMeshPiece done;
  // A tile near the surface whose halo holds no sample (its neighbour's points all far) has no piece.
  if (!t.samples.empty()) {
    const SupportGrid grid = grid_of_tile(t);
    const QuietProgress quiet;
    done = mesh_cloud_piece(grid, params, lattice, inputs.kept, inputs.crease_angle, inputs.asked_cell,
                            inputs.least_cell, backend);
  }
  const TriangleMesh& mesh = done.piece.mesh;
  ByteWriter result;
  result.put(done.counts);
  result.put_array<std::uint64_t>(done.piece.vertex_key);
  result.put_array<vec3>(mesh.positions);
  result.put_array<vec3>(mesh.normals);
  result.put_array<float>(done.cell);
  result.put_array<std::array<int, 3>>(mesh.triangles);
  result.put_array<std::uint64_t>(done.piece.triangle_cube);
  result.put_array<std::int32_t>(done.piece.triangle_place);
  return result.take();
}

CloudMeshPiece mesh_result(std::span<const std::byte> result) {
  ByteReader in(result);
  CloudMeshPiece p;
  p.counts = in.get<MarchCounts>();
  p.piece.vertex_key = in.get_array<std::uint64_t>();
  p.piece.mesh.positions = in.get_array<vec3>();
  p.piece.mesh.normals = in.get_array<vec3>();
  p.cell = in.get_array<float>();
  p.piece.mesh.triangles = in.get_array<std::array<int, 3>>();
  p.piece.triangle_cube = in.get_array<std::uint64_t>();
  p.piece.triangle_place = in.get_array<std::int32_t>();
  const std::size_t nv = p.piece.vertex_key.size(), nt = p.piece.mesh.triangles.size();
  bool whole = p.piece.mesh.positions.size() == nv && p.piece.mesh.normals.size() == nv && p.cell.size() == nv &&
               p.piece.triangle_cube.size() == nt && p.piece.triangle_place.size() == nt;
  for (const auto& triangle : p.piece.mesh.triangles)
    for (const int v : triangle) whole = whole && v >= 0 && std::size_t(v) < nv;
  if (!whole) throw Error("a tile's piece of the mesh does not hold together");
  return p;
}

}  // namespace pss
