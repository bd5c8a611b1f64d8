// Marching a primary ray through the volume (§5.1): samples every b = k·h along the ray
// inside the volume's box; a sample that passes the fragment test is projected. If the
// projection γ lies within ε of r, r is the hit, where the data have a surface there
// (surface_cells.hpp); otherwise the ray is intersected with the polynomial, and if that
// point lies in the ball of radius b around the sample it is projected in turn; else the
// sample is rejected and the march goes on. The first accepted sample wins (the paper's
// depth test).
#pragma once

#include <cstdint>

#include "pss/core/hit.hpp"
#include "pss/volume/bricks.hpp"
#include "pss/volume/projection.hpp"

namespace pss {

struct VolumeScene {
  FieldView fields;
  CellView cells;
  BrickView bricks;
  FeatureParams feature;
  VolumeParams params;
};

// Slab test; false when the ray misses the box. Unlike the BVH's ray_box (spatial/bvh.hpp),
// made for its inner loop, this runs once per ray and also settles rays parallel to a face
// with their origin on its plane, where ray_box's 0·∞ is undefined.
PSS_INLINE bool clip_to_box(const Ray& ray, const Aabb& box, float& t0, float& t1) {
  t0 = 0;
  t1 = kInfinity;
  for (int a = 0; a < 3; ++a) {
    const float inv = 1.0f / ray.dir[a];
    float ta = (box.lo[a] - ray.origin[a]) * inv, tb = (box.hi[a] - ray.origin[a]) * inv;
    if (ta > tb) swap(ta, tb);
    if (is_finite(ta)) t0 = max(t0, ta);
    if (is_finite(tb)) t1 = min(t1, tb);
    if (ray.dir[a] == 0 && (ray.origin[a] < box.lo[a] || ray.origin[a] > box.hi[a])) return false;
  }
  return t0 <= t1;
}

// The ray parameter of the ray/polynomial intersection nearest to x = ray.at(t) inside the
// ball B(r, b), or infinity. The ray is taken into the polynomial's frame from x.
PSS_INLINE float intersection_in_ball(const VolumeProjection& proj, const Ray& ray, float t, vec3 r, float b) {
  const vec3 x = ray.at(t);
  float roots[2];
  const int count = intersect_graph(proj.polynomial, proj.frame.to_local(x), proj.frame.direction_to_local(ray.dir), roots);
  float best = kInfinity;
  for (int i = 0; i < count; ++i)
    if (length2(ray.at(t + roots[i]) - r) <= b * b && abs(roots[i]) < abs(best)) best = roots[i];
  return best < kInfinity ? t + best : kInfinity;
}

// Projects from the sample r, retrying from ray/polynomial intersections inside the ball
// B(r, b). Returns true with the hit filled in when some projection lands within ε.
//
// The corrector runs only where its result could be accepted. It moves P(r) by a fraction
// of a voxel (the paper's Figure 2: few points farther than ε), so where the predictor
// alone moved the point farther than kCorrectorReach·ε, γ cannot come within ε of it: the
// predictor's polynomial then gives the next point on the ray (or rejects the sample when
// it misses the ball) without the corrector's cost. Every accepted hit is still a full
// predictor-corrector projection within ε. (--debug-projection runs the corrector on each
// ray's first sample regardless, to show what it does there.)
//
// The predictor also stops early once it has moved the point farther than kCorrectorReach·ε
// (Predictor): such a projection nearly always ends beyond that reach, where its polynomial
// only decides where the ray goes next. Where the unconverged polynomial meets the ray
// outside the ball B(r, b), the sample is rejected there (the one approximation: a few
// silhouette hits are lost, docs/benchmarks.md); otherwise the predictor resumes, to
// convergence or its iteration cap, and all goes on as if it had never stopped: every hit
// and every next point comes from full projections. Most such samples are rejected.
inline constexpr float kCorrectorReach = 4.0f;

template <class Nb>
PSS_HOST_DEVICE bool resolve_sample(const VolumeScene& s, const Ray& ray, float t_sample, Hit& hit, bool first,
                                    Nb& nb) {
  const VolumeParams& p = s.params;
  const vec3 r = ray.at(t_sample);
  const float eps2 = p.epsilon * p.epsilon;
  float t = t_sample;
  for (int attempt = 0; attempt <= p.max_retries; ++attempt) {
    const vec3 x = ray.at(t);
    const bool record = p.debug_projection && first && attempt == 0;
    Predictor<Nb> predictor(s.fields, x);
    VolumeProjection proj = predictor.run(p, nb, record ? kInfinity : kCorrectorReach * p.epsilon);
    ++hit.iterations;
    if (proj.stopped_early) {
      if (!(intersection_in_ball(proj, ray, t, r, p.step) < kInfinity)) return false;
      proj = predictor.run(p, nb);
    }
    if (proj.status != VolumeProjectionStatus::ok) return false;
    if (record && length2(proj.predicted - x) > eps2) hit.flags |= kHitPredictorMoved;
    const bool could_accept = length2(proj.point - x) <= kCorrectorReach * kCorrectorReach * eps2;
    if (p.method == VolumeMethod::predictor_corrector && (could_accept || record)) {
      proj = correct(s.fields, p, proj, nb);
      if (record && length2(proj.point - proj.predicted) > eps2) hit.flags |= kHitCorrectorMoved;
      if (proj.status != VolumeProjectionStatus::ok) return false;
    }
    if (length2(proj.point - x) <= eps2) {
      // Settled, but only a hit where the data has a surface (surface_cells.hpp).
      if (!is_data_surface(s.fields, s.cells, s.feature, x, proj.normal, p.surface_reach())) return false;
      hit.t = t;
      hit.point = x;
      hit.normal = proj.normal;  // along ∇f
      hit.flags |= kHitFound | kHitConverged;
      return true;
    }
    t = intersection_in_ball(proj, ray, t, r, p.step);
    if (!(t < kInfinity)) return false;
  }
  return false;
}

// Marches up to t_max (kInfinity for primary rays).
PSS_INLINE Hit march_volume(const VolumeScene& s, const Ray& ray, float t_max = kInfinity) {
  Hit hit;
  float t0, t1;
  if (!clip_to_box(ray, s.fields.volume.bounds(), t0, t1)) return hit;
  t1 = min(t1, t_max);
  const float b = s.params.step;
  const VolumeView& v = s.fields.volume;
  const vec3 grid_origin = v.to_grid(ray.origin);
  const vec3 grid_dir = ray.dir / v.spacing;
  bool first = true;
  VoxelScratch nb;
  // Samples t0 + j·b, indexed by j so that skipping lands exactly on the lattice.
  const float last = (t1 - t0) / b;
  for (float j = 0; j <= last;) {
    const float t = t0 + j * b;
    const vec3 g = grid_origin + t * grid_dir;
    const ivec3 brick = s.bricks.brick_of(g);
    if (!s.bricks.is_occupied(brick)) {
      // Leave the brick: the smallest exit parameter over the three slabs, then the first
      // lattice sample after it.
      float exit = kInfinity;
      for (int a = 0; a < 3; ++a) {
        if (grid_dir[a] == 0) continue;
        const float face = float(grid_dir[a] > 0 ? (brick[a] + 1) * kBrickCells : brick[a] * kBrickCells);
        exit = min(exit, (face - grid_origin[a]) / grid_dir[a]);
      }
      j = max(j + 1, floor((exit - t0) / b) + 1);
      continue;
    }
    if (passes_feature_test(s.fields, s.cells, s.feature, ray.at(t), s.params.sample_reach())) {
      if (resolve_sample(s, ray, t, hit, first, nb)) return hit;
      first = false;
    }
    j += 1;
  }
  return hit;
}

}  // namespace pss
