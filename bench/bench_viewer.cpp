// The viewer's interaction (issue 11): `pss view` under xvfb-run turns the camera through
// --turns views, waiting for each to refine, and reports (its "view timing" lines) how soon
// the first, reduced frame is on screen after the camera moved and how soon the full-size one
// is, with the render time of each. Medians over the turns; the first turn (no full-frame time
// known yet, so it starts at 1/4) is left out.
//   build/bench/bench_viewer [--turns 8] [--size 512x512] [--backend cpu] [--json FILE]
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "pss/io/output_file.hpp"

namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  int turns = 8;
  std::string size = "512x512", backend = "cpu", json_path = "bench-viewer.json";
  CLI::App app{"pss view's frame times as the camera turns (under xvfb-run)"};
  app.add_option("--turns", turns, "camera turns (medians over the second on)")
      ->check(CLI::Range(2, 1000))->capture_default_str();
  app.add_option("--size", size, "the window, WxH")->capture_default_str();
  app.add_option("--backend", backend)
      ->check(CLI::IsMember({"cpu", "cuda", "auto"}))->capture_default_str();
  app.add_option("--json", json_path, "the rows as JSON")->capture_default_str();
  CLI11_PARSE(app, argc, argv);
  if (std::system("command -v xvfb-run >/dev/null 2>&1") != 0) {
    std::fprintf(stderr, "bench_viewer: xvfb-run is not installed (apt-get install xvfb)\n");
    return 1;
  }
  const fs::path scratch = fs::temp_directory_path() / ("pss-bench-viewer-" + std::to_string(::getpid()));
  fs::create_directories(scratch);
  {
    std::ofstream script(scratch / "turns.txt");
    for (int t = 0; t < turns; ++t) script << "view " << 360.0 * t / turns << " " << 10 * (t % 3) << "\nwait\n";
  }
  struct Case {
    const char* name;
    std::string args;
  };
  const std::vector<Case> cases{
      {"bunny, 2 iterations, one reflection ray", PSS_SOURCE_DIR "/data/bun_zipper.ply --reflections"},
      {"engine, iso 90, predictor-corrector", PSS_SOURCE_DIR "/data/engine_256x256x128_uint8.nrrd --iso 90"},
  };
  std::printf("### The viewer: a camera turn to the first and the full-size frame (%s, %s, xvfb-run)\n\n"
              "| data | first frame | its render s | on screen after s | full-size render s | full size after s |\n"
              "|---|---|---|---|---|---|\n",
              size.c_str(), backend.c_str());
  json rows = json::array();
  for (const Case& c : cases) {
    const fs::path out = scratch / "out.txt";
    const std::string command = "timeout 900 xvfb-run -a -s '-screen 0 2048x2048x24' " + std::string(PSS_CLI) + " view " + c.args +
                                " --size " + size + " --backend " + backend + " --script " +
                                (scratch / "turns.txt").string() + " --screenshot-dir " + scratch.string() + " >" +
                                out.string() + " 2>&1";
    if (std::system(command.c_str()) != 0) {
      std::printf("| %s | failed (see %s) | | | | |\n", c.name, out.c_str());
      continue;
    }
    std::ifstream in(out);
    std::vector<double> first_render, first_after, full_render, full_after;
    std::vector<int> factors;
    int seen = 0;
    for (std::string line; std::getline(in, line);) {
      int factor = 0;
      double a = 0, b = 0, cc = 0, d = 0;
      if (std::sscanf(line.c_str(), "view timing: first frame at 1/%d in %lf s (its render %lf s), full size in %lf s (its render %lf s)",
                      &factor, &a, &b, &cc, &d) != 5 || seen++ == 0)
        continue;
      factors.push_back(factor);
      first_after.push_back(a);
      first_render.push_back(b);
      full_after.push_back(cc);
      full_render.push_back(d);
    }
    std::sort(factors.begin(), factors.end());
    const int factor = factors.empty() ? 0 : factors[factors.size() / 2];
    std::printf("| %s | 1/%d | %.4f | %.4f | %.4f | %.4f |\n", c.name, factor, median(first_render),
                median(first_after), median(full_render), median(full_after));
    std::fflush(stdout);
    rows.push_back({{"data", c.name}, {"size", size}, {"backend", backend}, {"turns", factors.size()},
                    {"first_factor", factor}, {"first_render_seconds", median(first_render)},
                    {"first_on_screen_seconds", median(first_after)}, {"full_render_seconds", median(full_render)},
                    {"full_on_screen_seconds", median(full_after)}});
  }
  fs::remove_all(scratch);
  pss::write_text_file(json_path, json{{"benchmark", "viewer"}, {"rows", rows}}.dump(2) + "\n");
  std::printf("\nwrote %s\n", json_path.c_str());
}
