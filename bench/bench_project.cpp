// Projection throughput of `pss project` (points per second): the bunny and a 10⁶-point
// torus (with --large also 10⁷, run once on the CPU), on the CPU and, when there is one, the
// GPU (--backend picks one), for each surface of --surfaces (issue 26). Median of --runs
// runs of the projection phase; APSS and RIMLS first need the samples' normals: the tori
// carry their exact ones, the bunny's are estimated and oriented (the "normals s" column).
//   build/bench/bench_project [--runs 5] [--large] [--backend all] [--surfaces mls,apss,rimls]
//                             [--json out/bench/project.json]
#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "pss/backend/backend.hpp"
#include "pss/io/output_file.hpp"
#include "pss/io/ply.hpp"
#include "pss/points/project_cloud.hpp"
#include "pss/points/spacing.hpp"
#include "support/shapes.hpp"

using namespace pss;

int main(int argc, char** argv) {
  int runs = 5;
  std::string json_path = "out/bench/project.json";
  bool large = false;
  std::string backend_choice = "all";
  std::vector<std::string> surfaces{"mls", "apss", "rimls"};
  CLI::App app{"pss project's throughput on the bunny and sampled tori"};
  app.add_option("--runs", runs, "runs per row (the median is reported)")
      ->check(CLI::Range(1, 100))->capture_default_str();
  app.add_option("--json", json_path, "the rows as JSON")->capture_default_str();
  app.add_flag("--large", large, "add a torus of 10^7 points");
  app.add_option("--backend", backend_choice, "the backends measured: cpu, cuda (when there is a device), or all")
      ->check(CLI::IsMember({"cpu", "cuda", "all"}))->capture_default_str();
  app.add_option("--surfaces", surfaces, "the surfaces measured (--surface of pss project)")
      ->delimiter(',')->check(CLI::IsMember({"mls", "apss", "rimls"}))->capture_default_str();
  CLI11_PARSE(app, argc, argv);
  struct Dataset {
    std::string name;
    PointCloud cloud;
  };
  std::vector<Dataset> datasets;
  datasets.push_back({"bunny (data/bun_zipper.ply)", read_ply(PSS_SOURCE_DIR "/data/bun_zipper.ply")});
  test::SampleOptions torus;
  torus.count = 1000000;
  torus.noise = 0.005f * test::Torus{}.minor;
  // With the exact normals as input normals: orienting 10⁶ and more unoriented normals (a
  // serial spanning tree) would take longer than the projection itself.
  const auto with_normals = [](PointCloud cloud) {
    cloud.normals.resize(cloud.size());
    for (std::size_t i = 0; i < cloud.size(); ++i) cloud.normals[i] = test::Torus{}.normal(cloud.positions[i]);
    return cloud;
  };
  datasets.push_back({"torus, 10^6 points, noise 0.5%, input normals", with_normals(test::sample(test::Torus{}, torus))});
  if (large) {
    torus.count = 10000000;
    datasets.push_back({"torus, 10^7 points, noise 0.5%, input normals", with_normals(test::sample(test::Torus{}, torus))});
  }

  std::vector<Backend> backends;
  if (backend_choice != "cuda") backends.push_back(Backend::cpu);
  if (backend_choice != "cpu" && cuda::built() && cuda::device_count() > 0) backends.push_back(Backend::cuda);
  if (backends.empty()) {
    std::fprintf(stderr, "bench_project: --backend cuda: no CUDA device (or a build without CUDA)\n");
    return 1;
  }

  nlohmann::json rows = nlohmann::json::array();
  std::printf("| dataset | points | surface | backend | h | normals s | median s | points/s |\n"
              "|---|---|---|---|---|---|---|---|\n");
  for (const Dataset& d : datasets) {
    const float h = float(estimate_spacing(d.cloud.positions).suggested_h);
    for (const std::string& surface : surfaces) {
      ProjectionParams params = ProjectionParams::from_h(h);
      params.surface = surface_operator_of(surface);
      for (Backend b : backends) {
        std::vector<double> seconds;
        double normals = 0;
        const int n_runs = d.cloud.size() <= 1000000 ? runs : b == Backend::cpu ? 1 : std::min(runs, 3);
        for (int r = 0; r < n_runs; ++r) {
          Stats stats;
          project_cloud(d.cloud, params, b, stats);
          seconds.push_back(stats.time("projection"));
          normals = stats.time("sample normals") + stats.time("orient normals");
        }
        std::sort(seconds.begin(), seconds.end());
        const double median = seconds[seconds.size() / 2];
        const std::string backend = b == Backend::cuda ? "cuda (" + cuda::device_name() + ")"
                                                       : "cpu (" + std::to_string(cpu_threads()) + " threads)";
        std::printf("| %s | %zu | %s | %s | %.5g | %.3f | %.4f | %.0f |\n", d.name.c_str(), d.cloud.size(),
                    surface.c_str(), backend.c_str(), h, normals, median, double(d.cloud.size()) / median);
        std::fflush(stdout);
        rows.push_back({{"dataset", d.name}, {"points", d.cloud.size()}, {"surface", surface}, {"backend", backend},
                        {"h", h}, {"runs", n_runs}, {"normals_seconds", normals}, {"median_seconds", median},
                        {"points_per_second", d.cloud.size() / median}, {"all_seconds", seconds}});
      }
    }
  }
  std::filesystem::create_directories(std::filesystem::path(json_path).parent_path());
  write_text_file(json_path, nlohmann::json{{"benchmark", "project"}, {"rows", rows}}.dump(2) + "\n");
  std::printf("wrote %s\n", json_path.c_str());
}
