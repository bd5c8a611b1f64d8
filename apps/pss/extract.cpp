// pss extract FILE (--iso V | --gradient) -o OUT.ply|.xyz: the PSS of a volume as an oriented
// point set, about one point per b (predictor-corrector); `pss render` can ray trace it.
#include <chrono>
#include <cstdio>

#include "commands.hpp"
#include "output_options.hpp"
#include "pss/io/output_file.hpp"
#include "pss/io/point_cloud_file.hpp"
#include "pss/volume/extract.hpp"
#include "volume_options.hpp"

namespace pss::app {

namespace {

struct ExtractOptions {
  VolumeOptions volume;
  std::string output;
  ComputeOptions compute;
};

void run_extract(const ExtractOptions& o) {
  const auto start = std::chrono::steady_clock::now();
  OutputSet outputs({o.volume.input}, {o.output, o.compute.stats_path});
  const Backend backend = start_compute(o.compute);
  Stats stats;
  const PreparedVolume volume = load_volume(o.volume, stats);
  ExtractionCounts counts;
  const PointCloud cloud = extract_surface(volume, backend, stats, counts);
  {
    ScopedPhase phase(stats, "write");
    write_point_cloud(o.output, cloud);
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  stats.add_time("total", seconds);
  std::printf("extracted %lld points from %s in %.3f s (projection %.3f s, %s backend, %s): "
              "%lld candidates, %lld accepted, b = %g\n", (long long)counts.kept, o.volume.input.c_str(), seconds,
              stats.time("projection"), backend_name(backend), threads_text().c_str(), (long long)counts.candidates,
              (long long)counts.accepted, volume.params.step);
  if (!o.compute.stats_path.empty()) {
    record_run(stats, "extract", o.volume.input, o.output, backend);
    auto& j = stats.values();
    j["candidates"] = counts.candidates;
    j["accepted"] = counts.accepted;
    j["points"] = counts.kept;
    j["volume"] = describe(volume, o.volume);
    stats.write(o.compute.stats_path);
  }
  outputs.commit();
  std::printf("wrote %s\n", o.output.c_str());
  if (!o.compute.stats_path.empty()) std::printf("wrote %s\n", o.compute.stats_path.c_str());
  if (counts.kept == 0)  // an empty file: say so, as pss volume does of an empty image
    std::fprintf(stderr, "pss extract: no point of %s lies on the surface (%lld cells cross it)\n",
                 o.volume.input.c_str(), (long long)volume.cells.crossed_count);
}

}  // namespace

void add_extract_command(CLI::App& app, Action action) {
  auto* command = app.add_subcommand("extract", "Extract the PSS of a volume as an oriented point set: .ply, .xyz");
  auto o = std::make_shared<ExtractOptions>();
  add_volume_options(*command, o->volume, false);
  command->add_option("-o,--output", o->output, "output points x y z nx ny nz, the normals along the gradient (toward higher values: inward where the object is the brighter), by extension: .ply (binary) or .xyz (text)")
      ->required()
      ->check(points_output());
  add_compute_options(*command, o->compute);
  command->callback([o, action] {
    if (action == Action::run) run_extract(*o);
    else check_volume_options(o->volume);
  });
}

}  // namespace pss::app
