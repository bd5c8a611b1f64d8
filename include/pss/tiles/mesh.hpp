// `pss mesh` of a cloud tile by tile (issue 28): a cloud on disk (TiledCloud) meshed within a
// memory budget. The samples are made ready as `pss project` makes them (tiles/project.hpp:
// widths, outliers, their normals, the file's or oriented over the tiles, their seams turned);
// then each tile marches the cubes
// of the lattice whose centres lie in it (mesh/mesh_cloud_piece.hpp), from its samples and a
// halo wide enough that its corners are the in-core ones, and the pieces are welded at the
// seams by their vertices' keys (mesh/weld.hpp): no cracks, no duplicate vertices. The
// welded mesh is held whole for the coarsening and the rest of mesh_cloud's last steps.
// The counts of work (corners, cubes visited and refused, crease flips) are the tiles'
// marches', margins included; the cubes crossed and the crease vertices are the mesh's own.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <vector>

#include "pss/backend/backend.hpp"
#include "pss/core/stats.hpp"
#include "pss/io/tiled_cloud.hpp"
#include "pss/mesh/mesh_cloud.hpp"
#include "pss/tiles/farm.hpp"

namespace pss {

struct TiledCloudMesh {
  CloudMesh mesh;
  std::vector<std::uint64_t> points_per_rank;  // the tiles' own points each rank meshed
  std::uint64_t normals_without_direction = 0;  // points' in the file (then all were left out)
};

// The mesh of `cloud`'s PSS with `params`, as mesh_cloud's, its steps' scratch files in
// `folder` (each buffered in at most `buffer_bytes`, the orientation's windows of
// `window_points`). Throws Error as mesh_cloud does, and NotTiled (tiles/memory_plan.hpp)
// for what tiles do not do yet: adaptive widths in a cloud sampled in rows.
TiledCloudMesh mesh_in_tiles(const TiledCloud& cloud, const MeshParams& params, Backend backend,
                             const std::filesystem::path& folder, std::size_t window_points,
                             std::size_t buffer_bytes, Stats& stats, TileFarm& farm = local_farm());

}  // namespace pss
