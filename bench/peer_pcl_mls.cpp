// Side by side, in one run: `pss project` against PCL's MovingLeastSquares (order 2, about
// 40 neighbours, the peer in shared/ANCHORS.md) on the bunny and on noisy spheres and tori
// (σ = 0.5% of the radius): seconds (median of --runs) and, where the truth is analytic,
// mean distance to the surface and mean normal angle.
//   build/bench/peer_pcl_mls [--runs 5] [--json out/bench/peer_pcl_mls.json]
#include <pcl/point_types.h>
#include <pcl/search/kdtree.h>
#include <pcl/surface/mls.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <functional>
#include <optional>

#include <CLI/CLI.hpp>

#include "pss/backend/backend.hpp"
#include "pss/io/output_file.hpp"
#include "pss/io/ply.hpp"
#include "pss/points/project_cloud.hpp"
#include "pss/points/spacing.hpp"
#include "support/shapes.hpp"

using namespace pss;

namespace {

struct Quality {
  double mean_distance = 0, mean_angle_deg = 0;
};

using Truth = std::function<std::pair<float, vec3>(vec3)>;  // signed distance and normal

Quality measure(const std::vector<vec3>& points, const std::vector<vec3>& normals, const Truth& truth) {
  Quality q;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const auto [d, n] = truth(points[i]);
    q.mean_distance += std::abs(d) / points.size();
    q.mean_angle_deg += std::acos(std::min(1.0f, std::abs(glm::dot(n, normals[i])))) * 180 / M_PI / points.size();
  }
  return q;
}

template <class F>
double median_seconds(int runs, F&& f) {
  std::vector<double> s;
  for (int r = 0; r < runs; ++r) {
    const auto start = std::chrono::steady_clock::now();
    f();
    s.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  std::sort(s.begin(), s.end());
  return s[s.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  int runs = 5;
  std::string json_path = "out/bench/peer_pcl_mls.json";
  CLI::App app{"pss project against PCL's MovingLeastSquares, side by side"};
  app.add_option("--runs", runs, "runs per row (the median is reported)")
      ->check(CLI::Range(1, 100))->capture_default_str();
  app.add_option("--json", json_path, "the rows as JSON")->capture_default_str();
  CLI11_PARSE(app, argc, argv);
  const int threads = cpu_threads();
  struct Dataset {
    std::string name;
    PointCloud cloud;
    float scale;  // the radius errors are reported in
    std::optional<Truth> truth;
  };
  test::SampleOptions noisy;
  noisy.count = 36000;
  noisy.noise = 0.005f;
  const test::Sphere sphere;
  const test::Torus torus;
  test::SampleOptions noisy_torus = noisy;
  noisy_torus.noise = 0.005f * torus.minor;
  std::vector<Dataset> datasets;
  datasets.push_back({"bunny", read_ply(PSS_SOURCE_DIR "/data/bun_zipper.ply"), 1.0f, std::nullopt});
  datasets.push_back({"sphere R=1, σ=0.5%R", test::sample(sphere, noisy), 1.0f,
                      Truth([&](vec3 p) { return std::pair{sphere.distance(p), sphere.normal(p)}; })});
  datasets.push_back({"torus r=0.35, σ=0.5%r", test::sample(torus, noisy_torus), torus.minor,
                      Truth([&](vec3 p) { return std::pair{torus.distance(p), torus.normal(p)}; })});

  nlohmann::json rows = nlohmann::json::array();
  std::printf("| dataset | method | seconds | mean distance / R | mean normal angle |\n|---|---|---|---|---|\n");
  for (const Dataset& d : datasets) {
    // pss as `pss project` runs it (h from the spacing), with either plane fit. PCL's
    // default projection fits a PCA plane, then the polynomial: the counterpart of our WLS.
    const float h = float(estimate_spacing(d.cloud.positions).suggested_h);
    CloudProjection ours, ours_wls;
    const double ours_s = median_seconds(runs, [&] {
      Stats stats;
      ours = project_cloud(d.cloud, ProjectionParams::from_h(h, PlaneFitMethod::mls), Backend::cpu, stats);
    });
    const double ours_wls_s = median_seconds(runs, [&] {
      Stats stats;
      ours_wls = project_cloud(d.cloud, ProjectionParams::from_h(h, PlaneFitMethod::wls), Backend::cpu, stats);
    });

    // PCL: order 2 with a radius that holds ~40 neighbours, Gaussian parameter radius².
    pcl::PointCloud<pcl::PointXYZ>::Ptr input(new pcl::PointCloud<pcl::PointXYZ>);
    for (const vec3& p : d.cloud.positions) input->push_back(pcl::PointXYZ(p.x, p.y, p.z));
    const double radius = estimate_spacing(d.cloud.positions, 40).median_kth;
    pcl::PointCloud<pcl::PointNormal> theirs;
    const double theirs_s = median_seconds(runs, [&] {
      pcl::MovingLeastSquares<pcl::PointXYZ, pcl::PointNormal> mls;
      mls.setInputCloud(input);
      mls.setSearchMethod(pcl::search::KdTree<pcl::PointXYZ>::Ptr(new pcl::search::KdTree<pcl::PointXYZ>));
      mls.setComputeNormals(true);
      mls.setPolynomialOrder(2);
      mls.setSearchRadius(radius);
      mls.setNumberOfThreads(threads);
      theirs.clear();
      mls.process(theirs);
    });

    std::vector<vec3> pp, pn;
    for (const auto& q : theirs) {
      pp.emplace_back(q.x, q.y, q.z);
      pn.emplace_back(q.normal_x, q.normal_y, q.normal_z);
    }
    auto row = [&](const char* method, double s, std::optional<Quality> q, std::size_t points) {
      if (q)
        std::printf("| %s | %s | %.3f | %.5f | %.2f° |\n", d.name.c_str(), method, s, q->mean_distance / d.scale,
                    q->mean_angle_deg);
      else
        std::printf("| %s | %s | %.3f | — | — |\n", d.name.c_str(), method, s);
      nlohmann::json j{{"dataset", d.name}, {"method", method}, {"median_seconds", s}, {"points_out", points},
                       {"threads", threads}, {"runs", runs}};
      if (q) j["mean_distance_over_radius"] = q->mean_distance / d.scale, j["mean_normal_angle_deg"] = q->mean_angle_deg;
      rows.push_back(j);
    };
    std::optional<Quality> qi, qo, qw, qt;
    if (d.truth) {
      qi = measure(d.cloud.positions, std::vector<vec3>(d.cloud.size(), vec3(0, 0, 1)), *d.truth);
      qo = measure(ours.cloud.positions, ours.cloud.normals, *d.truth);
      qw = measure(ours_wls.cloud.positions, ours_wls.cloud.normals, *d.truth);
      qt = measure(pp, pn, *d.truth);
      std::printf("| %s | input | — | %.5f | — |\n", d.name.c_str(), qi->mean_distance / d.scale);
    }
    row("pss project (MLS, default h)", ours_s, qo, ours.cloud.size());
    row("pss project --method wls", ours_wls_s, qw, ours_wls.cloud.size());
    row("PCL MovingLeastSquares (order 2, ~40 neighbours)", theirs_s, qt, pp.size());
    std::fflush(stdout);
  }
  std::filesystem::create_directories(std::filesystem::path(json_path).parent_path());
  write_text_file(json_path, nlohmann::json{{"benchmark", "peer_pcl_mls"}, {"rows", rows}}.dump(2) + "\n");
  std::printf("wrote %s\n", json_path.c_str());
}
