// The paper's Tables 1 and 2 on our hardware, plus scaling: runs the `pss` CLI as a user
// would (with --stats) and reports frames per second of the per-frame phases (primary,
// secondary, shading; preprocessing and acceleration structures are built once, as in the
// paper). Median of --runs runs. Clouds are rendered with the paper's operator (--surface
// mls), not the default RIMLS, so that the frame rates compare with the paper's and earlier rows.
// With --frames N each run renders N frames and counts the median one (pss --frames).
//   build/bench/bench_paper_tables [--runs 3] [--frames 1] [--backend cpu] [--json FILE] [--only table1|table2|scaling]
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "pss/io/output_file.hpp"
#include "pss/io/ply.hpp"
#include "support/shapes.hpp"

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

struct Options {
  int runs = 3;
  int frames = 1;
  std::string backend = "cpu";
  std::string json_path = "out/bench/paper_tables.json";
  std::string only;
  fs::path scratch;
};

// Runs `pss <args> --stats FILE` and returns the stats, or null when pss failed.
json run_pss(const Options& o, const std::string& args) {
  const fs::path stats = o.scratch / "stats.json";
  fs::remove(stats);
  const std::string command = std::string(PSS_CLI) + " " + args + " --backend " + o.backend +
                              " --frames " + std::to_string(o.frames) + " --stats " +
                              stats.string() + " >/dev/null 2>" + (o.scratch / "err.txt").string();
  const int status = std::system(command.c_str());
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    std::ifstream err(o.scratch / "err.txt");
    std::string line;
    std::getline(err, line);
    std::fprintf(stderr, "pss %s failed: %s\n", args.c_str(), line.c_str());
    return nullptr;
  }
  return json::parse(std::ifstream(stats));
}

double frame_seconds(const json& stats) {
  double s = 0;
  for (const char* phase : {"primary", "secondary", "shading"})
    if (stats["seconds"].contains(phase)) s += stats["seconds"][phase].get<double>();
  return s;
}

// Median frame time over runs; the last run's stats for the record.
struct Measured {
  double seconds = 0;
  json stats;
};
Measured measure(const Options& o, const std::string& args) {
  std::vector<double> s;
  Measured m;
  for (int r = 0; r < o.runs; ++r) {
    m.stats = run_pss(o, args);
    if (m.stats.is_null()) return {};
    s.push_back(frame_seconds(m.stats));
  }
  std::sort(s.begin(), s.end());
  m.seconds = s[s.size() / 2];
  return m;
}

std::string fps(double seconds) {
  char b[32];
  std::snprintf(b, sizeof b, "%.2f", seconds > 0 ? 1.0 / seconds : 0.0);
  return seconds > 0 ? b : "failed";
}

void table2(const Options& o, json& rows) {
  std::printf("\n### Table 2: ray tracing the PSS of a point cloud, 512², one reflection ray (depth 2)\n\n"
              "The default support (adaptive widths, issue 26) and the paper's one global h, alternating.\n\n"
              "| model | points | iterations | support | paper fps (6800 GT) | our fps (%s) | frame s |\n"
              "|---|---|---|---|---|---|---|\n",
              o.backend.c_str());
  const std::string bunny = PSS_SOURCE_DIR "/data/bun_zipper.ply";
  for (auto [iterations, paper] : {std::pair{2, 6.62}, std::pair{3, 5.30}}) {
    for (const char* support : {"adaptive", "global"}) {
      const Measured m = measure(o, "render " + bunny + " -o " + (o.scratch / "t2.png").string() +
                                        " --surface mls --size 512x512 --reflections --iterations " + std::to_string(iterations) +
                                        " --support " + support);
      std::printf("| Stanford Bunny | 35947 | %d | %s | %.2f | %s | %.4f |\n", iterations, support, paper,
                  fps(m.seconds).c_str(), m.seconds);
      std::fflush(stdout);
      rows.push_back({{"table", 2}, {"model", "bunny"}, {"iterations", iterations}, {"support", support},
                      {"paper_fps", paper}, {"backend", o.backend}, {"frame_seconds", m.seconds}, {"stats", m.stats}});
    }
  }
}

void table1(const Options& o, json& rows) {
  std::printf("\n### Table 1: PSS extraction from volumes, 512²\n\n"
              "| dataset | size | method | paper fps (6800 GT) | our fps (%s) | frame s |\n|---|---|---|---|---|---|\n",
              o.backend.c_str());
  struct Volume {
    const char* name;
    std::string path, dims, raw_flags, surface;
    double paper_predictor, paper_corrector;
  };
  const std::vector<Volume> volumes{
      {"Engine", PSS_SOURCE_DIR "/data/engine_256x256x128_uint8.nrrd", "256x256x128", "", "--iso 90", 1.16, 0.03},
      {"Fuel", PSS_SOURCE_DIR "/data/fuel_64x64x64_uint8.raw", "64x64x64", "--dims 64x64x64 --type uint8", "--iso 30",
       3.57, 0.08},
      {"Bucky", PSS_SOURCE_DIR "/data/bucky_32x32x32_uint8.raw", "32x32x32", "--dims 32x32x32 --type uint8",
       "--iso 100 --h 1.25", 7.16, 0.17}};
  for (const Volume& v : volumes) {
    if (!fs::exists(v.path)) {
      std::printf("| %s | %s | — | — | missing %s | — |\n", v.name, v.dims.c_str(), v.path.c_str());
      continue;
    }
    for (auto [method, paper] : {std::pair{"predictor", v.paper_predictor}, std::pair{"predictor-corrector", v.paper_corrector}}) {
      const Measured m = measure(o, "volume " + v.path + " " + v.raw_flags + " " + v.surface +
                                        " --method " + method + " --size 512x512 -o " + (o.scratch / "t1.png").string());
      std::printf("| %s | %s | %s | %.2f | %s | %.4f |\n", v.name, v.dims.c_str(), method, paper,
                  fps(m.seconds).c_str(), m.seconds);
      std::fflush(stdout);
      rows.push_back({{"table", 1}, {"dataset", v.name}, {"method", method}, {"paper_fps", paper},
                      {"backend", o.backend}, {"frame_seconds", m.seconds}, {"stats", m.stats}});
    }
  }
}

void scaling(const Options& o, json& rows) {
  std::printf("\n### Scaling: sampled torus, 512², 2 iterations, one reflection ray\n\n"
              "| points | our fps (%s) | frame s | preprocess s | BVH s |\n|---|---|---|---|---|\n", o.backend.c_str());
  for (std::size_t n : {10000u, 100000u, 1000000u}) {
    pss::test::SampleOptions s;
    s.count = n;
    const fs::path cloud = o.scratch / ("torus" + std::to_string(n) + ".ply");
    pss::write_ply(cloud, pss::test::sample(pss::test::Torus{}, s));
    const Measured m = measure(o, "render " + cloud.string() + " -o " + (o.scratch / "sc.png").string() +
                                      " --surface mls --size 512x512 --reflections --iterations 2");
    const double pre = m.stats.is_null() ? 0 : m.stats["seconds"].value("preprocess", 0.0);
    const double bvh = m.stats.is_null() ? 0 : m.stats["seconds"].value("acceleration structure", 0.0);
    std::printf("| %zu | %s | %.4f | %.3f | %.3f |\n", n, fps(m.seconds).c_str(), m.seconds, pre, bvh);
    std::fflush(stdout);
    rows.push_back({{"scaling", "points"}, {"points", n}, {"backend", o.backend}, {"frame_seconds", m.seconds},
                    {"stats", m.stats}});
  }
  {
    // The interactive case of a large scan: 10⁶ points, full HD, shadows and a reflection.
    const fs::path cloud = o.scratch / "torus1000000.ply";
    const Measured m = measure(o, "render " + cloud.string() + " -o " + (o.scratch / "sc.png").string() +
                                      " --surface mls --size 1920x1080 --shadows --reflections --iterations 2");
    std::printf("\n| 1000000, 1920×1080, shadows and reflection | %s | %.4f | — | — |\n", fps(m.seconds).c_str(),
                m.seconds);
    std::fflush(stdout);
    rows.push_back({{"scaling", "points"}, {"points", 1000000}, {"size", "1920x1080"}, {"shadows", true},
                    {"backend", o.backend}, {"frame_seconds", m.seconds}, {"stats", m.stats}});
  }
  std::printf("\n### Scaling: bunny, 2 iterations, one reflection ray\n\n| size | rays | our fps (%s) | frame s |\n|---|---|---|---|\n",
              o.backend.c_str());
  for (const char* size : {"256x256", "512x512", "1024x1024", "1920x1080"}) {
    const Measured m = measure(o, std::string("render ") + PSS_SOURCE_DIR "/data/bun_zipper.ply -o " +
                                      (o.scratch / "sc.png").string() + " --surface mls --reflections --iterations 2 --size " + size);
    int w = 0, h = 0;
    std::sscanf(size, "%dx%d", &w, &h);
    std::printf("| %s | %d | %s | %.4f |\n", size, w * h, fps(m.seconds).c_str(), m.seconds);
    std::fflush(stdout);
    rows.push_back({{"scaling", "resolution"}, {"size", size}, {"backend", o.backend}, {"frame_seconds", m.seconds},
                    {"stats", m.stats}});
  }
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  CLI::App app{"The paper's Tables 1 and 2 and the scaling runs, through the pss CLI"};
  app.add_option("--runs", o.runs, "runs per row (the median is reported)")
      ->check(CLI::Range(1, 100))->capture_default_str();
  app.add_option("--frames", o.frames, "frames per run (pss --frames)")
      ->check(CLI::Range(1, 100))->capture_default_str();
  app.add_option("--backend", o.backend)
      ->check(CLI::IsMember({"cpu", "cuda", "auto"}))->capture_default_str();
  app.add_option("--json", o.json_path, "the rows as JSON")->capture_default_str();
  app.add_option("--only", o.only, "one part")
      ->check(CLI::IsMember({"table1", "table2", "scaling"}));
  CLI11_PARSE(app, argc, argv);
  o.scratch = fs::temp_directory_path() / ("pss-bench-" + std::to_string(::getpid()));
  fs::create_directories(o.scratch);
  json rows = json::array();
  if (o.only.empty() || o.only == "table2") table2(o, rows);
  if (o.only.empty() || o.only == "table1") table1(o, rows);
  if (o.only.empty() || o.only == "scaling") scaling(o, rows);
  fs::remove_all(o.scratch);
  if (!fs::path(o.json_path).parent_path().empty()) fs::create_directories(fs::path(o.json_path).parent_path());
  pss::write_text_file(o.json_path, json{{"benchmark", "paper_tables"}, {"runs", o.runs}, {"frames", o.frames}, {"rows", rows}}.dump(2) + "\n");
  std::printf("\nwrote %s\n", o.json_path.c_str());
}
