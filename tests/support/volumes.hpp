// Analytic volumes for the volume tests: a sampled scalar field with its exact iso-surface
// (or maximal-gradient surface), distances and normals to check against, optionally
// quantised to 8 bits and with seeded additive Gaussian noise.
#pragma once

#include <cmath>
#include <cstdint>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include "pss/core/stats.hpp"
#include "pss/io/volume_file.hpp"
#include "pss/volume/render_volume.hpp"
#include "pss/volume/volume.hpp"

namespace pss::test {

// An analytic scalar field f with its gradient; the surface is f = iso.
struct Field {
  std::function<float(vec3)> value;
  std::function<vec3(vec3)> gradient;
  float iso = 0;

  // First-order distance of p to the surface: |f(p) − v| / |∇f(p)|, exact for distance
  // fields and within O(d²·curvature of f) for the others.
  float distance(vec3 p) const { return std::abs(value(p) - iso) / glm::length(gradient(p)); }
  vec3 normal(vec3 p) const { return glm::normalize(gradient(p)); }
};

// Signed distance to a sphere: f = |p − c| − R, iso 0.
inline Field sphere_distance(vec3 c, float radius) {
  return {[=](vec3 p) { return glm::length(p - c) - radius; },
          [=](vec3 p) { return glm::normalize(p - c); }, 0.0f};
}

// Torus around the z axis through c: major radius R, tube radius r.
inline Field torus_distance(vec3 c, float major, float minor) {
  return {[=](vec3 p) {
            const vec3 d = p - c;
            const float q = std::sqrt(d.x * d.x + d.y * d.y) - major;
            return std::sqrt(q * q + d.z * d.z) - minor;
          },
          [=](vec3 p) {
            const vec3 d = p - c;
            const float rho = std::sqrt(d.x * d.x + d.y * d.y);
            const vec3 ring = vec3(d.x / rho * major, d.y / rho * major, 0.0f);
            return glm::normalize(d - ring);
          },
          0.0f};
}

// A smooth indicator of a distance field: amplitude / (1 + exp(d / width)). |∇f| peaks
// exactly on d = 0, the surface the gradient mode must find (iso is then amplitude / 2).
inline Field smooth_indicator(const Field& distance_field, float amplitude, float width) {
  return {[=](vec3 p) { return amplitude / (1.0f + std::exp(distance_field.value(p) / width)); },
          [=](vec3 p) {
            const float e = std::exp(distance_field.value(p) / width);
            return -amplitude * e / ((1 + e) * (1 + e) * width) * distance_field.gradient(p);
          },
          amplitude / 2};
}

// Σ aᵢ·exp(−|p − cᵢ|²/sᵢ²).
struct Blob {
  vec3 center;
  float amplitude, width;
};
inline Field gaussian_blobs(std::vector<Blob> blobs, float iso) {
  return {[=](vec3 p) {
            float f = 0;
            for (const Blob& b : blobs) f += b.amplitude * std::exp(-length2(p - b.center) / (b.width * b.width));
            return f;
          },
          [=](vec3 p) {
            vec3 g(0.0f);
            for (const Blob& b : blobs)
              g += -2.0f * b.amplitude / (b.width * b.width) * std::exp(-length2(p - b.center) / (b.width * b.width)) *
                   (p - b.center);
            return g;
          },
          iso};
}

struct SampleVolumeOptions {
  ivec3 dims{48};
  vec3 spacing{1.0f};
  vec3 origin{0.0f};
  float noise = 0;      // standard deviation of the additive noise, value units
  bool quantize = false;  // round to 8 bits after scale·f + offset, clamped to [0, 255]
  float scale = 1, offset = 0;
  std::uint32_t seed = 7;
};

// The field sampled at the voxels: scale·f + offset + noise, quantised if asked. The
// surface of the sampled volume is then value = scale·iso + offset.
inline Volume sample_volume(const Field& f, const SampleVolumeOptions& o) {
  Volume v;
  v.dims = o.dims;
  v.spacing = o.spacing;
  v.origin = o.origin;
  v.values.resize(std::size_t(v.voxel_count()));
  std::mt19937 rng(o.seed);
  std::normal_distribution<float> noise(0.0f, o.noise > 0 ? o.noise : 1.0f);
  const VolumeView view = v.view();
  for (int k = 0; k < o.dims.z; ++k)
    for (int j = 0; j < o.dims.y; ++j)
      for (int i = 0; i < o.dims.x; ++i) {
        float x = o.scale * f.value(view.position(i, j, k)) + o.offset;
        if (o.noise > 0) x += noise(rng);
        if (o.quantize) x = std::round(std::fmin(std::fmax(x, 0.0f), 255.0f));
        v.values[std::size_t(view.index(i, j, k))] = x;
      }
  return v;
}

// A headerless uint8 raw file of f over `dims` unit voxels, as the CLI tests write them:
// 100 − 40·f rounded, so that the surface f = 0 is the iso-value 100.
inline std::string uint8_raw_bytes(const Field& f, ivec3 dims) {
  SampleVolumeOptions o;
  o.dims = dims;
  o.quantize = true;
  o.scale = -40;
  o.offset = 100;
  std::string bytes;
  for (float x : sample_volume(f, o).values) bytes.push_back(char(std::uint8_t(x)));
  return bytes;
}

// How the shipped raw scans are read: uint8, x fastest, unit spacing.
inline RawVolumeFormat uint8_raw(ivec3 dims) {
  RawVolumeFormat f;
  f.dims = dims;
  f.type = VoxelType::uint8;
  return f;
}

// The iso-surface f = iso of a unit-spaced volume, prepared for rendering or extraction
// with `params` (by default the documented defaults).
inline PreparedVolume prepare_iso(const Volume& volume, float iso,
                                  const VolumeParams& params = VolumeParams::from_voxels(1.0f)) {
  Stats stats;
  VolumeFields fields = compute_fields(volume);
  const FeatureParams feature = iso_feature(iso, kIsoSmoothingVoxels * fields.volume.view().voxel_size());
  return prepare_volume(std::move(fields), feature, params, stats);
}

}  // namespace pss::test
