// Checks shared by the volume tests: hits against an analytic surface (distances,
// normals, the share of its silhouette covered), and a render of an analytic volume through
// the library as `pss volume` does it.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "pss/render/camera.hpp"
#include "support/volumes.hpp"

namespace pss::test {

struct Accuracy {
  std::int64_t hits = 0;
  double rms_distance = 0, max_distance = 0;
  double rms_normal_deg = 0, max_normal_deg = 0;
};

inline float angle_deg(vec3 a, vec3 b) {
  return std::acos(std::min(1.0f, std::abs(glm::dot(glm::normalize(a), glm::normalize(b))))) * 57.29578f;
}

template <class Points>
Accuracy measure(const Field& truth, const Points& points) {
  Accuracy a;
  double d2 = 0, n2 = 0;
  for (const auto& [p, n] : points) {
    const double d = truth.distance(p), angle = angle_deg(n, truth.normal(p));
    d2 += d * d;
    n2 += angle * angle;
    a.max_distance = std::max(a.max_distance, d);
    a.max_normal_deg = std::max(a.max_normal_deg, angle);
    ++a.hits;
  }
  if (a.hits) {
    a.rms_distance = std::sqrt(d2 / double(a.hits));
    a.rms_normal_deg = std::sqrt(n2 / double(a.hits));
  }
  return a;
}

struct Rendered {
  RenderedFrame frame;
  std::vector<std::pair<vec3, vec3>> hits;
};

// 64×64 rays from an oblique view, like `pss volume --view 30,20 --size 64x64`; the
// neighbourhoods' radius 1.5h, as the CLI's default.
inline Rendered render(const Volume& volume, std::optional<float> iso, VolumeMethod method, float h_voxels = 2.0f,
                CameraSettings view = {64, 64, 30, 20, 35}) {
  Stats stats;
  VolumeFields fields = compute_fields(volume);
  const VolumeParams params = VolumeParams::from_voxels(fields.volume.view().voxel_size(), method, h_voxels, 0.75f,
                                                        0.9f, 0.1f, 1.5f * h_voxels);
  const float voxel = fields.volume.view().voxel_size();
  const FeatureParams feature = iso ? iso_feature(*iso, kIsoSmoothingVoxels * voxel) : gradient_feature();
  const PreparedVolume prepared = prepare_volume(std::move(fields), feature, params, stats);
  const Camera camera = Camera::framing(prepared.fields.volume.view().bounds(), view);
  TraceSettings settings;
  Rendered out;
  out.frame = render_volume(prepared, camera, settings, Backend::cpu, stats);
  for (const Hit& h : out.frame.hits)
    if (h.found()) out.hits.emplace_back(h.point, h.normal);
  return out;
}

// Rays that cross the analytic surface inside the volume's box: a sign change of f − v
// between steps of 0.05 voxels.
inline std::int64_t pixels_covered(const Field& truth, const Camera& camera, const Aabb& box) {
  std::int64_t n = 0;
  for (int y = 0; y < camera.height; ++y)
    for (int x = 0; x < camera.width; ++x) {
      const Ray ray = camera.primary_ray(x, y);
      float t0, t1;
      if (!clip_to_box(ray, box, t0, t1)) continue;
      bool below = truth.value(ray.at(t0)) < truth.iso;
      for (float t = t0; t <= t1; t += 0.05f) {
        if ((truth.value(ray.at(t)) < truth.iso) != below) {
          ++n;
          break;
        }
      }
    }
  return n;
}

// What one rendered surface must meet: the share of the analytic silhouette's pixels that
// hit, rms and max distance (voxels), rms normal angle (degrees).
struct SurfaceBounds {
  int min_coverage_percent;
  double rms, max, normal_rms;
};

// Measures the hits of `r` against `truth`, logs the figures and checks them.
inline void expect_surface(const std::string& name, const Field& truth, const Volume& volume, const Rendered& r,
                    SurfaceBounds b) {
  const Accuracy a = measure(truth, r.hits);
  const std::int64_t covered = pixels_covered(truth, r.frame.camera, volume.view().bounds());
  std::printf("%s: %lld hits of %lld covered, rms %.3f max %.3f voxels, normals rms %.2f max %.2f deg\n",
              name.c_str(), (long long)a.hits, (long long)covered, a.rms_distance, a.max_distance, a.rms_normal_deg,
              a.max_normal_deg);
  EXPECT_GT(a.hits, covered * b.min_coverage_percent / 100) << name;
  EXPECT_LT(a.rms_distance, b.rms) << name;
  EXPECT_LT(a.max_distance, b.max) << name;
  EXPECT_LT(a.rms_normal_deg, b.normal_rms) << name;
}

}  // namespace pss::test
