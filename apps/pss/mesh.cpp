// pss mesh FILE -o OUT.ply|.obj|.stl|.off: a triangle mesh of the PSS of a point cloud or of a
// volume (issue 27), its vertices on the surface with the surface's normals.
#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <optional>
#include <span>
#include <string>

#include "commands.hpp"
#include "in_tiles_or_core.hpp"
#include "numbers.hpp"
#include "output_options.hpp"
#include "pss/core/error.hpp"
#include "pss/io/mesh_file.hpp"
#include "pss/io/output_file.hpp"
#include "pss/io/point_cloud_file.hpp"
#include "pss/io/point_stream.hpp"
#include "pss/io/tiled_cloud.hpp"
#include "pss/mesh/mesh_cloud.hpp"
#include "pss/mesh/mesh_stats.hpp"
#include "pss/mesh/mesh_volume.hpp"
#include "pss/points/border_choice.hpp"
#include "pss/tiles/memory_plan.hpp"
#include "pss/tiles/mesh.hpp"
#include "pss/tiles/spacing.hpp"
#include "ranks/ranks.hpp"
#include "volume_options.hpp"

namespace pss::app {

namespace {

struct MeshOptions {
  std::string input, output;
  float cell = 0;
  float crease_angle = kDefaultCreaseAngle;
  CloudSurfaceFlags surface;  // its --h serves volumes too, in voxels
  std::string borders = "auto";
  VolumeOptions volume;       // a volume's flags
  ComputeOptions compute;
  std::string memory;  // --memory SIZE
  CLI::App* command = nullptr;
};

// Bytes a point (tiles/memory_plan.hpp): in core, the mesh's band at its peak (the 10^6-point
// noisy torus: 980 MiB once, 424 MiB now; docs/benchmarks.md); beside the tiles, each point's
// width and flags and the welded mesh, held whole for its coarsening (that torus's: 1.23 M
// vertices and 2.46 M triangles before it, whose weld and coarsening took 387 MiB); a tile's
// point and its halo's as project's, with its band.
constexpr MemoryCosts kMeshCosts{1024, 448, 1536};

// The flags that only a cloud's PSS, or only a volume's, takes.
constexpr const char* kCloudFlags[] = {"--rho",        "--support", "--surface",      "--normals", "--outliers",
                                       "--iterations", "--borders", "--crease-angle", "--memory"};
constexpr const char* kVolumeFlags[] = {"--iso",   "--gradient", "--method", "--radius",
                                        "--alpha", "--smoothing", "--error", "--threshold"};

// A volume has a header (.nrrd, .mhd, .nii, ...) or is raw, described by --dims and --type.
bool is_volume(const MeshOptions& o) { return has_volume_header(o.input) || raw_volume_format(o.volume.raw, o.input); }

// `pss volume`'s options of this mesh's volume: its input, and --h as the volume's width.
VolumeOptions volume_options(const MeshOptions& o) {
  VolumeOptions options = o.volume;
  options.input = o.input;
  if (o.surface.h != 0) options.settings.h = o.surface.h;
  return options;
}

// The flags of the other kind of data refused, the volume's checked together; reads nothing.
void check_mesh_options(const MeshOptions& o) {
  const bool volume = is_volume(o);
  using Flags = std::span<const char* const>;
  const Flags others = volume ? Flags(kCloudFlags) : Flags(kVolumeFlags);
  for (const char* flag : others)
    if (o.command->get_option(flag)->count() > 0)
      throw Error(std::string(flag) + " applies to " + (volume ? "point clouds" : "volumes") + " only, and " +
                  o.input + " is " +
                  (volume ? "a volume" : "read as a point cloud (a volume has a header, or is raw with --dims)"));
  if (!volume) return;
  check_volume_options(volume_options(o));
  if (o.surface.h != 0 && o.surface.h < kMinVolumeH) {
    char message[160];
    std::snprintf(message, sizeof message, "--h: a volume's h is in voxels, at least %g (got %g)", double(kMinVolumeH),
                  double(o.surface.h));
    throw Error(message);
  }
}

// Writes the mesh, adds the run's total time, and prints what the mesh is (of `size`: the
// points or voxels it was made from).
MeshTopology write_and_summarise(const MeshOptions& o, const TriangleMesh& mesh, const std::string& size,
                                 Backend backend, Stats& stats, std::chrono::steady_clock::time_point start) {
  const MeshTopology shape = topology(mesh);
  {
    ScopedPhase phase(stats, "write");
    write_mesh(o.output, mesh);
  }
  const double total = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  stats.add_time("total", total);
  std::printf("meshed %s (%s) in %.3f s (%s backend, %s): %lld vertices, %lld triangles, %lld "
              "component%s, %s, %lld boundary edges, Euler characteristic %lld\n",
              o.input.c_str(), size.c_str(), total, backend_name(backend), threads_text().c_str(), (long long)shape.vertices,
              (long long)shape.triangles, (long long)shape.components, shape.components == 1 ? "" : "s",
              shape.watertight() ? "watertight" : shape.manifold() ? "manifold with boundaries" : "NOT manifold",
              (long long)shape.boundary_edges, (long long)shape.euler_characteristic());
  return shape;
}

// What pss mesh says of a cloud's mesh, in core or tile by tile, and records in --stats.
void summarise_cloud_mesh(const MeshOptions& o, const CloudMesh& result, const MeshParams& params,
                          const MeshTopology& shape, Stats& stats) {
  std::printf("%s surface%s, h = %g (%s), rho = %g, borders %s, cell %g; %lld corners evaluated, %lld cubes meshed, "
              "%lld vertices on creases, %lld merged into neighbours; %lld outliers set aside, "
              "%lld part%s held by fewer than %d samples removed\n",
              surface_name(params.projection.surface), normals_text(result.normals), double(params.projection.h),
              support_text(params.projection.support, result.widths).c_str(), double(params.projection.rho),
              border_name(params.projection.borders), double(result.cell), (long long)result.counts.corners,
              (long long)result.counts.cubes_crossed, (long long)result.counts.crease_vertices,
              (long long)result.counts.collapsed_vertices, (long long)result.outliers.set_aside,
              (long long)result.counts.unsupported_parts, result.counts.unsupported_parts == 1 ? "" : "s", kMinPartSamples);
  if (result.turned_outward)
    std::printf("the normals' orientation faced inward (the closed parts enclosed a negative volume): the mesh "
                "was turned to face outward\n");
  if (!o.compute.stats_path.empty()) record_cloud_mesh(stats, result, params, shape);
}

// A cloud of fewer than 3 points, before any work.
void check_mesh_points(const std::string& input, std::uint64_t points) {
  if (points < 3)
    throw file_error(input, "has " + std::to_string(points) + (points == 1 ? " point" : " points") +
                                ": a mesh needs at least 3");
}

MeshParams mesh_params(const MeshOptions& o, ProjectionParams projection, bool mesh_vertices) {
  MeshParams params;
  params.projection = projection;
  params.projection.borders =
      border_choice_of(o.borders).value_or(mesh_vertices ? BorderMode::clip : BorderMode::extend);
  params.cell = o.cell;
  params.crease_angle = o.crease_angle;
  return params;
}

void mesh_cloud_in_core(const MeshOptions& o, Backend backend, Stats& stats,
                        std::chrono::steady_clock::time_point start) {
  const PointCloud cloud = read_cloud(o.input, stats);
  check_mesh_points(o.input, cloud.size());
  check_mesh_origin(o.output, cloud.origin);  // before the work, not after
  const MeshParams params = mesh_params(
      o, projection_params(o.surface, cloud, o.input, PlaneFitMethod::mls, stats), cloud.mesh_vertices);
  const CloudMesh result = naming_input(o.input, [&] { return mesh_cloud(cloud, params, backend, stats); });
  const MeshTopology shape =
      write_and_summarise(o, result.mesh, std::to_string(cloud.size()) + " points", backend, stats, start);
  if (!o.compute.stats_path.empty()) record_cloud_run(stats, "mesh", o.input, o.output, cloud, backend);
  summarise_cloud_mesh(o, result, params, shape, stats);
  print_normals_turned(result.normals_turned, cloud.size());
  print_file_normals_off(result.file_normals_off, cloud.size());
  print_file_normals_left_out(file_normals_without_direction(cloud, o.surface.surface), cloud.size());
}

// A cloud larger than the budget, or shared by ranks, tile by tile (issue 28, tiles/mesh.hpp).
void mesh_cloud_in_tiles(const MeshOptions& o, const MemoryPlan& plan, Backend backend, Stats& stats,
                         std::chrono::steady_clock::time_point start) {
  std::optional<TiledCloud> read;
  {
    ScopedPhase phase(stats, "read", false);  // its Progress shows it
    read.emplace(o.input, scratch_folder(), plan.points_per_tile, plan.buffer_bytes);
  }
  const TiledCloud& tiles = *read;
  check_mesh_points(o.input, tiles.size());
  check_mesh_origin(o.output, tiles.origin());
  const ProjectionParams projection = projection_params(
      o.surface, [&] { return naming_input(o.input, [&] { return float(estimate_spacing(tiles).suggested_h); }); },
      PlaneFitMethod::mls, stats);
  const MeshParams params = mesh_params(o, projection, open_point_stream(o.input)->mesh_vertices());
  // A window's records take about 64 bytes (the orientation's).
  const std::size_t window = std::size_t(std::clamp<std::uint64_t>(plan.budget / 8 / 64, 4096, 1u << 24));
  const TiledCloudMesh result = naming_input(o.input, [&] {
    return mesh_in_tiles(tiles, params, backend, scratch_folder(), window, plan.buffer_bytes, stats, rank_farm());
  });
  const std::string ranks = rank_count() > 1 ? ", " + std::to_string(rank_count()) + " ranks" : "";
  const MeshTopology shape =
      write_and_summarise(o, result.mesh.mesh,
                          std::to_string(tiles.size()) + " points, tile by tile: " + tiles_text(tiles) + ranks, backend,
                          stats, start);
  if (!o.compute.stats_path.empty()) {
    record_cloud_run(stats, "mesh", o.input, o.output, tiles.size(), tiles.origin(), backend);
    stats.values()["points_per_rank"] = result.points_per_rank;
  }
  summarise_cloud_mesh(o, result.mesh, params, shape, stats);
  print_normals_turned(result.mesh.normals_turned, std::size_t(tiles.size()));
  print_file_normals_off(result.mesh.file_normals_off, std::size_t(tiles.size()));
  print_file_normals_left_out(std::size_t(result.normals_without_direction), std::size_t(tiles.size()));
}

void run_cloud_mesh(const MeshOptions& o, Stats& stats, std::chrono::steady_clock::time_point start) {
  const Backend backend = start_compute(o.compute);
  const MemoryPlan plan = in_tiles_or_core(
      o.input, o.memory, kMeshCosts, stats,
      [&](const MemoryPlan& tiles) { mesh_cloud_in_tiles(o, tiles, backend, stats, start); },
      [&] { mesh_cloud_in_core(o, backend, stats, start); });
  if (!o.compute.stats_path.empty()) {
    auto& v = stats.values();
    v["memory"] = {{"budget", plan.budget}, {"tiled", plan.tiled}};
    if (plan.tiled) v["memory"]["points_per_tile"] = plan.points_per_tile;
    v["ranks"] = rank_count();
  }
}

void run_volume_mesh(const MeshOptions& o, Stats& stats, std::chrono::steady_clock::time_point start) {
  const Backend backend = start_compute(o.compute);
  const VolumeOptions options = volume_options(o);
  const PreparedVolume volume = load_volume(options, stats);
  const VolumeMesh result = naming_input(o.input, [&] { return mesh_volume(volume, o.cell, backend, stats); });
  const VolumeView view = volume.fields.volume.view();
  const MeshTopology shape = write_and_summarise(
      o, result.mesh,
      "volume " + std::to_string(view.dims.x) + "x" + std::to_string(view.dims.y) + "x" + std::to_string(view.dims.z),
      backend, stats, start);
  const float voxel = view.voxel_size();
  if (volume.feature.kind == FeatureKind::iso)
    std::printf("iso-surface %g", double(volume.feature.iso));
  else
    std::printf("gradient surface (threshold %g)", double(volume.feature.threshold));
  std::printf(" by the %s, h = %g voxels, cell %g (%g voxels); %lld corners evaluated, %lld cubes meshed, %lld "
              "vertices merged into neighbours\n",
              options.method.c_str(), double(volume.params.h / voxel), double(result.cell),
              double(result.cell / voxel), (long long)result.counts.corners, (long long)result.counts.cubes_crossed,
              (long long)result.counts.collapsed_vertices);

  if (!o.compute.stats_path.empty()) {
    record_run(stats, "mesh", o.input, o.output, backend);
    auto& v = stats.values();
    v["volume"] = describe(volume, options);
    v["cell"] = result.cell;
    record_mesh(stats, shape, result.counts);
  }
}

void run_mesh(const MeshOptions& o) {
  const auto start = std::chrono::steady_clock::now();
  check_mesh_options(o);
  OutputSet outputs({o.input}, {o.output, o.compute.stats_path});
  Stats stats;
  if (is_volume(o))
    run_volume_mesh(o, stats, start);
  else
    run_cloud_mesh(o, stats, start);
  if (!o.compute.stats_path.empty()) stats.write(o.compute.stats_path);
  outputs.commit();
  std::printf("wrote %s\n", o.output.c_str());
  if (!o.compute.stats_path.empty()) std::printf("wrote %s\n", o.compute.stats_path.c_str());
}

}  // namespace

void add_mesh_command(CLI::App& app, Action action) {
  auto* command = app.add_subcommand(
      "mesh", "A triangle mesh of the point set surface of a point cloud or a volume: .ply, .obj, .stl, .off");
  auto o = std::make_shared<MeshOptions>();
  o->command = command;
  command
      ->add_option("file", o->input,
                   kCloudFormatsHelp + " or volume (.nrrd/.nhdr, .mhd/.mha, .nii/.nii.gz, or raw with --dims and --type)")
      ->required();
  command
      ->add_option("-o,--output", o->output,
                   "output mesh, by extension: .ply (binary: x y z nx ny nz per vertex, the surface's normals; "
                   "triangles), .obj (v, vn, f), .stl (binary, facet normals) or .off")
      ->required()
      ->check(mesh_output());
  auto* clouds = command->add_option_group("Point clouds' PSS");
  auto* volumes = command->add_option_group("Volumes' PSS (--iso or --gradient)");
  add_cloud_surface_flags(*command, o->surface);  // --h serves both: the others move to their group
  add_memory_option(*command, o->memory, "the pieces welded at the seams into the in-core mesh (docs/architecture.md)");
  for (const char* flag : kCloudFlags)  // those of project's; the mesh's own are added to the group below
    if (CLI::Option* option = command->get_option_no_throw(flag)) clouds->add_option(option);
  command->get_option("--h")->description(
      "Gaussian width h: a cloud's in its units (default: estimated from the spacing and the noise, see pss info); a volume's "
      "theta3 width in voxels u = (sx*sy*sz)^(1/3), at least 0.5 (default 2)");
  command->add_option("--cell", o->cell,
                      "side of the cubes the surface is meshed in, and for a cloud the size its triangles grow to: "
                      "smaller gives more, smaller triangles (default: a cloud's h/2, cubes of the least, triangles "
                      "grown to the local h/2, at most rho/2: for coarser raise --h too; a volume's voxel u)")
      ->check(finite_positive());
  clouds->add_option("--borders", o->borders,
                      "where the mesh ends: clip (at its samples' hull), extend (as far as the projection "
                      "reaches, about rho past the last samples), or auto (clip for a mesh's vertices, whose surface "
                      "ends at them; extend for scans, whose points stand for the surface around them). Either way a "
                      "scan's open edge and its holes wider than about 2 rho stay open")
      ->check(CLI::IsMember({"auto", "clip", "extend"}))
      ->capture_default_str();
  clouds
      ->add_option("--crease-angle", o->crease_angle,
                   "degrees: where the surface's normals within a cube differ by more than this and the surface "
                   "has a sharp crease there (rimls keeps them; the other surfaces round them), a vertex is put on "
                   "the crease instead of cutting it off; 180: never")
      ->check(finite_range(0, 180, true))
      ->capture_default_str();
  add_raw_volume_options(*volumes, o->volume.raw);
  add_volume_surface_flags(*volumes, o->volume, true, false);
  add_compute_options(*command, o->compute);
  command->callback([o, action] {
    if (action == Action::run)
      run_mesh(*o);
    else
      check_mesh_options(*o);
  });
}

}  // namespace pss::app
