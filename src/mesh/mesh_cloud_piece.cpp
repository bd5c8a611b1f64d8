#include "pss/mesh/mesh_cloud_piece.hpp"

#include <glm/common.hpp>

#include "implicit_surface.hpp"
#include "vertex_cells.hpp"
#include "pss/core/stats.hpp"
#include "pss/mesh/cloud_implicit.hpp"
#include "pss/spatial/grid_mirror.hpp"

namespace pss {

CloudMeshPiece mesh_cloud_piece(const SupportGrid& grid, const ProjectionParams& params, const Lattice& lattice,
                                const CubeBox& kept, float crease_angle, float asked, float least, Backend backend) {
  Stats stats;  // the caller times the step whole
  const GridMirror g(backend, grid);
  const ImplicitSurface implicit =
      mesh_detail::implicit_surface(backend, CloudImplicit{g.view(), params}, float(lattice.cell), stats);
  const CubeBox marched{glm::max(kept.lo - kPieceMargin, ivec3(0)), glm::min(kept.hi + kPieceMargin, lattice.size - 1)};
  CloudMeshPiece out;
  out.piece = march_piece(lattice, grid.sorted_points(), implicit, mesh_detail::kMaxSlope, crease_angle, marched,
                          kept, out.counts);
  out.cell = mesh_detail::vertex_cells(out.piece.mesh.positions, grid, asked, least);
  return out;
}

}  // namespace pss
