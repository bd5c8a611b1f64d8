// `pss volume --iso v` on the shipped scans against the field's reference surface, the
// trilinear interpolant's crossing of v (tests/support/iso_reference.hpp; ANCHORS "Real
// data"): per case, object pixels (the reference hits), holes and phantom pixels as % of
// them, distance of pss's hits to the marching-tetrahedra mesh (mean, p99, voxels), mean
// normal angle where both hit, pss's frame time and the reference's.
//   build/bench/volume_vs_reference [--json out/bench/volume_vs_reference.json]
//                                   [--write-images DIR] [--size 256] [--only NAME]
// With --write-images, DIR/<volume>_iso<v>_az<a>_el<e>.png holds pss (left), the reference
// (middle, grey headlight diffuse) and where they disagree (right: red, pss has a surface
// the reference has not or is a voxel in front of it; blue, pss misses the reference's
// surface or is a voxel behind it) side by side.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "pss/io/output_file.hpp"
#include "pss/io/volume_file.hpp"
#include "pss/render/image.hpp"
#include "pss/volume/render_volume.hpp"
#include "support/iso_reference.hpp"
#include "support/volumes.hpp"

using namespace pss;

namespace {

struct Dataset {
  std::string name, file;
  std::optional<RawVolumeFormat> raw;  // none: NRRD
  std::vector<float> isos;
};

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

int main(int argc, char** argv) {
  std::string json_path = "out/bench/volume_vs_reference.json", images;
  int size = 256;
  std::string only;  // one dataset by name
  CLI::App app{"pss volume against the trilinear iso-surface reference on the real scans"};
  app.add_option("--json", json_path, "the rows as JSON")->capture_default_str();
  app.add_option("--write-images", images, "a folder for the images side by side");
  app.add_option("--size", size, "image side")->check(CLI::Range(8, 4096))->capture_default_str();
  app.add_option("--only", only, "one dataset by name (tooth, engine, fuel, bucky, ...)");
  CLI11_PARSE(app, argc, argv);
  if (!images.empty()) std::filesystem::create_directories(images);
  const std::vector<Dataset> datasets = {
      {"tooth", "tooth_103x94x161_uint8.raw", test::uint8_raw(ivec3(103, 94, 161)), {60, 110}},
      {"engine", "engine_256x256x128_uint8.nrrd", std::nullopt, {75, 180}},
      {"fuel", "fuel_64x64x64_uint8.raw", test::uint8_raw(ivec3(64, 64, 64)), {30, 100}},
      {"bucky", "bucky_32x32x32_uint8.raw", test::uint8_raw(ivec3(32, 32, 32)), {100, 200}},
      {"neghip", "neghip_64x64x64_uint8.raw", test::uint8_raw(ivec3(64, 64, 64)), {40, 120}},
  };
  const vec2 views[] = {{30, 10}, {200, -30}, {120, 60}};

  nlohmann::json rows = nlohmann::json::array();
  std::printf("| volume | iso | view | object px | holes %% | phantom %% | holes off rim %% | phantom off rim %% | "
              "in front %% | behind %% | mean dist (vox) | p99 dist (vox) | normal angle (deg) | pss frame s | "
              "reference s |\n|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (const Dataset& d : datasets) {
    if (!only.empty() && d.name != only) continue;
    const Volume volume = read_volume(std::filesystem::path(PSS_SOURCE_DIR "/data") / d.file, d.raw);
    const VolumeView v = volume.view();
    for (const float iso : d.isos) {
      const PreparedVolume prepared = test::prepare_iso(volume, iso);
      auto start = std::chrono::steady_clock::now();
      const test::ReferenceMesh mesh(v, iso);
      const double mesh_s = seconds_since(start);
      for (const vec2 view : views) {
        const Camera camera = test::volume_camera(prepared.surface_bounds(), size, size, view.x, view.y);
        const test::ReferenceMeasurement m = test::measure_against_reference(prepared, iso, camera, mesh);
        const test::ReferenceComparison& c = m.comparison;
        std::printf("| %s | %g | %g,%g | %lld | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f | %.3f | %.3f | %.2f | %.3f | "
                    "%.3f |\n", d.name.c_str(), iso, view.x, view.y, (long long)c.object_pixels, 100 * c.holes,
                    100 * c.phantom, 100 * c.interior_holes, 100 * c.exterior_phantom, 100 * c.in_front, 100 * c.behind, c.mean_distance, c.p99_distance, c.mean_normal_angle_deg,
                    m.pss_seconds, m.reference_seconds);
        std::fflush(stdout);
        rows.push_back({{"volume", d.name},
                        {"file", d.file},
                        {"iso", iso},
                        {"azimuth_deg", view.x},
                        {"elevation_deg", view.y},
                        {"width", size},
                        {"height", size},
                        {"object_pixels", c.object_pixels},
                        {"pss_hits", c.pss_hits},
                        {"hole_pixels", c.hole_pixels},
                        {"phantom_pixels", c.phantom_pixels},
                        {"holes", c.holes},
                        {"phantom", c.phantom},
                        {"interior_holes", c.interior_holes},
                        {"exterior_phantom", c.exterior_phantom},
                        {"in_front_pixels", c.in_front_pixels},
                        {"behind_pixels", c.behind_pixels},
                        {"in_front", c.in_front},
                        {"behind", c.behind},
                        {"mean_distance_voxels", c.mean_distance},
                        {"p99_distance_voxels", c.p99_distance},
                        {"max_distance_voxels", c.max_distance},
                        {"mean_depth_difference_voxels", c.mean_depth_difference},
                        {"mean_normal_angle_deg", c.mean_normal_angle_deg},
                        {"pss_frame_seconds", m.pss_seconds},
                        {"reference_seconds", m.reference_seconds},
                        {"mesh_triangles", mesh.triangles().size()},
                        {"mesh_seconds", mesh_s}});
        if (!images.empty()) {
          Image side(3 * size, size);
          const std::vector<vec3> ref = test::shade_reference(m.reference, camera);
          const std::vector<vec3> diff = test::disagreement_image(m.hits, m.reference, camera, v.voxel_size());
          for (int y = 0; y < size; ++y)
            for (int x = 0; x < size; ++x) {
              const std::size_t i = std::size_t(y * size + x);
              side.at(x, y) = m.pss_image[i];
              side.at(size + x, y) = ref[i];
              side.at(2 * size + x, y) = diff[i];
            }
          char name[160];
          std::snprintf(name, sizeof name, "%s_iso%g_az%g_el%g.png", d.name.c_str(), iso, view.x, view.y);
          write_png(std::filesystem::path(images) / name, side);
        }
      }
    }
  }
  std::filesystem::create_directories(std::filesystem::path(json_path).parent_path());
  write_text_file(json_path, nlohmann::json{{"benchmark", "volume_vs_reference"}, {"rows", rows}}.dump(2) + "\n");
  std::printf("wrote %s\n", json_path.c_str());
}
