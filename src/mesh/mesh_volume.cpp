#include "pss/mesh/mesh_volume.hpp"

#include <cmath>
#include <string>
#include <vector>

#include "implicit_surface.hpp"
#include "pss/core/error.hpp"
#include "pss/mesh/coarsen.hpp"
#include "pss/mesh/volume_implicit.hpp"

namespace pss {

namespace {

// A volume's PSS fits the smoothed field over h ≥ 0.5 voxels (θ1, §4), so its creases are
// rounded at the scale of the cubes: none is snapped (mesh_cloud.hpp: kDefaultCreaseAngle).
constexpr float kNoCreases = 180;

// The band starts at the centres of the cells the surface crosses (surface_cells.hpp), one
// in every piece of it however small, and grows from there.
std::vector<vec3> crossed_cell_centres(const PreparedVolume& volume) {
  const VolumeView v = volume.fields.volume.view();
  const SurfaceCells& cells = volume.cells;
  std::vector<vec3> centres;
  centres.reserve(std::size_t(cells.crossed_count));
  for (int k = 0; k < cells.count.z; ++k)
    for (int j = 0; j < cells.count.y; ++j)
      for (int i = 0; i < cells.count.x; ++i)
        if (cells.view().at(ivec3(i, j, k)) & kCellCrossed)
          centres.push_back(v.origin + (vec3(float(i), float(j), float(k)) + 0.5f) * v.spacing);
  return centres;
}

}  // namespace

VolumeMesh mesh_volume(const PreparedVolume& volume, float cell, Backend backend, Stats& stats) {
  if (!(cell >= 0) || !std::isfinite(cell))
    throw Error("the cell size must be a positive number (got " + std::to_string(cell) + ")");
  const VolumeView view = volume.fields.volume.view();
  const float voxel = view.voxel_size();
  VolumeMesh out;
  out.cell = cell > 0 ? cell : kDefaultCellVoxels * voxel;
  const Aabb box = view.bounds();
  const Lattice lattice = lattice_over(box.lo, box.hi, 2.0 * double(out.cell), double(out.cell), "the cell size");
  // About one crossed cell per voxel² of surface, and one cube per cell² of it.
  const double ratio = double(voxel) / double(out.cell);
  const double band_cubes = double(volume.cells.crossed_count) * ratio * ratio;
  check_band(band_cubes, double(out.cell), "volume");
  const std::vector<vec3> seeds = crossed_cell_centres(volume);

  const SceneMirror scene(backend, volume);
  const ImplicitSurface implicit =
      mesh_detail::implicit_surface(backend, VolumeImplicit{scene.scene(), out.cell}, out.cell, stats);
  {
    ScopedPhase phase(stats, "mesh", false);  // its kernels show their progress
    out.mesh = march_tetrahedra(lattice, seeds, implicit, mesh_detail::kMaxSlope, kNoCreases, out.counts,
                                std::int64_t(kCornersPerBandCube * band_cubes));
  }
  {
    // The march's slivers, where the surface passes near a lattice corner, merge into their
    // neighbours (coarsen.hpp); the cell is one size, the voxel's, so nothing else grows.
    ScopedPhase phase(stats, "coarsen", true);
    coarsen_mesh(out.mesh, std::vector<float>(out.mesh.positions.size(), out.cell), out.counts);
  }
  if (out.mesh.triangles.empty())
    throw Error(volume.cells.crossed_count == 0
                    ? std::string("the volume has no surface to mesh: no cell of it holds the feature")
                    : std::string("the surface gave no triangle: the data reach the iso-value without crossing "
                                  "it, or the cell is too large for the surface"));
  return out;
}

}  // namespace pss
