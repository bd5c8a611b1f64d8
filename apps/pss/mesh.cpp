// pss mesh FILE -o OUT.ply|.obj|.stl|.off: a triangle mesh of the PSS of a point cloud
// (issue 27), its vertices on the surface with the surface's normals.
#include <chrono>
#include <cstdio>
#include <string>

#include "commands.hpp"
#include "numbers.hpp"
#include "output_options.hpp"
#include "pss/core/error.hpp"
#include "pss/io/mesh_file.hpp"
#include "pss/io/output_file.hpp"
#include "pss/io/point_cloud_file.hpp"
#include "pss/mesh/mesh_cloud.hpp"
#include "pss/points/border_choice.hpp"

namespace pss::app {

namespace {

struct MeshOptions {
  std::string input, output;
  float cell = 0;
  CloudSurfaceFlags surface;
  std::string borders = "auto";
  ComputeOptions compute;
};

void run_mesh(const MeshOptions& o) {
  const auto start = std::chrono::steady_clock::now();
  OutputSet outputs({o.input}, {o.output, o.compute.stats_path});
  const Backend backend = start_compute(o.compute);
  Stats stats;
  const PointCloud cloud = read_cloud(o.input, stats);
  if (cloud.size() < 3)
    throw file_error(o.input, "has " + std::to_string(cloud.size()) + " points: a mesh needs at least 3");
  MeshParams params;
  params.projection = projection_params(o.surface, cloud, o.input, PlaneFitMethod::mls, stats);
  params.projection.borders = borders_for(border_choice_of(o.borders), cloud);
  params.cell = o.cell;

  CloudMesh result;
  try {
    result = mesh_cloud(cloud, params, backend, stats);
  } catch (const Error& e) {
    throw file_error(o.input, e.what());
  }
  const MeshTopology shape = topology(result.mesh);
  {
    ScopedPhase phase(stats, "write");
    write_mesh(o.output, result.mesh);
  }
  const double total = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  stats.add_time("total", total);

  std::printf("meshed %s (%zu points) in %.3f s (%s backend, %d threads): %lld vertices, %lld triangles, %lld "
              "component%s, %s, %lld boundary edges, Euler characteristic %lld\n",
              o.input.c_str(), cloud.size(), total, backend_name(backend), cpu_threads(), (long long)shape.vertices,
              (long long)shape.triangles, (long long)shape.components, shape.components == 1 ? "" : "s",
              shape.watertight() ? "watertight" : shape.manifold() ? "manifold with boundaries" : "NOT manifold",
              (long long)shape.boundary_edges, (long long)shape.euler_characteristic());
  std::printf("%s surface%s, h = %g (%s), rho = %g, borders %s, cell %g; %lld corners evaluated, %lld cubes meshed; "
              "%lld outliers set aside\n",
              surface_name(params.projection.surface), normals_text(result.normals), double(params.projection.h),
              support_text(params.projection.support, result.widths).c_str(), double(params.projection.rho),
              border_name(params.projection.borders), double(result.cell), (long long)result.counts.corners,
              (long long)result.counts.cubes_crossed, (long long)result.outliers.set_aside);
  print_normals_turned(result.normals_turned, cloud.size());
  if (result.turned_outward)
    std::printf("the normals' orientation faced inward (the closed parts enclosed a negative volume): the mesh "
                "was turned to face outward\n");

  if (!o.compute.stats_path.empty()) {
    auto& v = stats.values();
    record_cloud_run(stats, "mesh", o.input, o.output, cloud, backend);
    v["params"] = {{"h", params.projection.h}, {"rho", params.projection.rho}, {"cell", result.cell},
                   {"support", support_name(params.projection.support)},
                   {"surface", surface_name(params.projection.surface)}, {"normals", normals_used_name(result.normals)},
                   {"outliers", o.surface.surface.outliers}, {"borders", border_name(params.projection.borders)},
                   {"h_least", result.widths.least}, {"h_largest", result.widths.largest},
                   {"max_mls_iterations", params.projection.max_mls_iterations}};
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
    v["band"] = {{"corners", result.counts.corners},
                 {"cubes_visited", result.counts.cubes_visited},
                 {"cubes_meshed", result.counts.cubes_crossed},
                 {"cubes_refused", result.counts.cubes_refused},
                 {"pinched_triangles", result.counts.pinched_triangles}};
    v["outliers_set_aside"] = result.outliers.set_aside;
    v["normals_turned"] = result.normals_turned;
    v["turned_outward"] = result.turned_outward;
    stats.write(o.compute.stats_path);
  }
  outputs.commit();
  std::printf("wrote %s\n", o.output.c_str());
  if (!o.compute.stats_path.empty()) std::printf("wrote %s\n", o.compute.stats_path.c_str());
}

}  // namespace

void add_mesh_command(CLI::App& app, Action action) {
  auto* command =
      app.add_subcommand("mesh", "A triangle mesh of the point set surface of a point cloud: .ply, .obj, .stl, .off");
  auto o = std::make_shared<MeshOptions>();
  command->add_option("file", o->input, "point cloud (.ply, .xyz/.txt/.pts, .pwn, .obj, .off, .stl, .pcd, .las)")
      ->required();
  command
      ->add_option("-o,--output", o->output,
                   "output mesh, by extension: .ply (binary: x y z nx ny nz per vertex, the surface's normals; "
                   "triangles), .obj (v, vn, f), .stl (binary, facet normals) or .off")
      ->required()
      ->check(mesh_output());
  add_cloud_surface_flags(*command, o->surface);
  command->add_option("--cell", o->cell,
                      "side of the cubes the surface is meshed in: smaller gives more, smaller triangles (default h/2, "
                      "about the samples' spacing)")
      ->check(finite_positive());
  command->add_option("--borders", o->borders,
                      "where the mesh ends: clip (at its samples' hull), extend (as far as the projection reaches, "
                      "about rho past the last samples), or auto (clip for a mesh's vertices, whose surface ends at "
                      "them; extend for scans, whose points stand for the surface around them). Either way a scan's "
                      "open edge and its holes wider than about 2 rho stay open")
      ->check(CLI::IsMember({"auto", "clip", "extend"}))
      ->capture_default_str();
  add_compute_options(*command, o->compute);
  command->callback([o, action] {
    if (action == Action::run) run_mesh(*o);
  });
}

}  // namespace pss::app
