#include "pss/mesh/mesh_stats.hpp"

#include "pss/points/surface_stats.hpp"

namespace pss {

void record_mesh(Stats& stats, const MeshTopology& shape, const MarchCounts& counts) {
  auto& v = stats.values();
  v["mesh"] = {{"vertices", shape.vertices},
               {"triangles", shape.triangles},
               {"edges", shape.edges},
               {"components", shape.components},
               {"boundary_edges", shape.boundary_edges},
               {"non_manifold_edges", shape.non_manifold_edges},
               {"non_manifold_vertices", shape.non_manifold_vertices},
               {"euler_characteristic", shape.euler_characteristic()},
               {"watertight", shape.watertight()},
               {"manifold", shape.manifold()}};
  v["band"] = {{"corners", counts.corners},
               {"cubes_visited", counts.cubes_visited},
               {"cubes_meshed", counts.cubes_crossed},
               {"cubes_refused", counts.cubes_refused},
               {"crease_vertices", counts.crease_vertices},
               {"crease_flips", counts.crease_flips},
               {"pinched_triangles", counts.pinched_triangles},
               {"normals_turned", counts.normals_turned},
               {"collapsed_vertices", counts.collapsed_vertices},
               {"unsupported_parts", counts.unsupported_parts},
               {"closed_parts_turned", counts.closed_parts_turned}};
}

void record_cloud_mesh(Stats& stats, const CloudMesh& made, const MeshParams& params, const MeshTopology& shape) {
  record_cloud_surface(stats, params.projection, made.widths, made.normals, made.normals_turned, made.file_normals_off,
                       made.outliers.set_aside);
  auto& p = stats.values()["params"];
  p["cell"] = made.cell;
  p["crease_angle"] = params.crease_angle;
  p["borders"] = border_name(params.projection.borders);
  record_mesh(stats, shape, made.counts);
  stats.values()["turned_outward"] = made.turned_outward;
}

}  // namespace pss
