// Intersecting a ray with the PSS of a point cloud (paper §5.2, after Adamson and Alexa
// [AA03b]): the nearest local polynomial g_i inside its ball B(p_i, b_i) gives a candidate r;
// r is projected onto the PSS; if the projection γ is within ε of r, r is the hit;
// otherwise the ray is intersected with the new polynomial and, while that point stays in
// B(p_i, b_i), the projection repeats from it; if it leaves the ball the candidate is
// rejected and the search goes on to the next ball intersection beyond it.
#pragma once

#include "pss/points/local_polynomials.hpp"
#include "pss/points/surface_projection.hpp"
#include "pss/core/hit.hpp"
#include "pss/spatial/bvh.hpp"

namespace pss {

enum class SecondaryMode : unsigned char {
  paper,  // the first local-polynomial hit, no projection (what the paper could afford)
  full,   // the full projection loop, as for primary rays
};

// The lengths are at h (ProjectionParams): with adaptive support each sample's b_i, δ_i and
// ε_i scale with its h_i/h, and a hit's secondary offset with the hit's (Hit::scale).
struct RayPssParams {
  ProjectionParams projection;  // WLS plane (paper §5.2 uses WLS for r), ρ = 2h
  float ball_radius = 0;        // b
  // δ: a sample's polynomial is left out where one kept within δ_k passes within
  // kThinningTolerance·h_k of it (points/thinning.hpp); 0 keeps one per sample, as the paper.
  float ball_spacing = 0;
  float epsilon = 0;            // accept r when |γ − r| < ε
  int max_iterations = 2;       // projections per candidate (paper Table 2: 2 and 3)
  int max_candidates = 0;       // ball intersections tried per ray before giving up
  SecondaryMode secondary = SecondaryMode::full;
  float secondary_offset = 0;   // secondary rays start this far off the surface

  // Defaults from h (docs/paper-notes.md):
  // - b = h: the polynomial of p_i is fitted with weights exp(−d²/h²), so beyond about h it
  //   is an extrapolation; b = h also keeps neighbouring balls overlapping (spacing ≈ h/2
  //   for the default h), so the surface has no gaps between them.
  // - ε = 1e-3·h: well below a pixel at any scale at which h is resolved, and above the
  //   float rounding of a projection (~1e-6 of the coordinates).
  // - δ = b/2: every surface point within b/2 of a sample then lies within b of a kept
  //   polynomial's sample, inside its ball; δ = 0.6b lets grazing rays through a sphere's
  //   silhouette (tests/ray_pss_test.cpp).
  // - borders extend, the paper's: projection.borders = clip bounds the surface by its
  //   samples (points/borders.hpp), what `pss render` chooses for a mesh's vertices.
  // - offset = b/2: a secondary ray leaves from above the neighbours' polynomials, which
  //   follow the surface to within noise, and so does not re-hit its own surface.
  static RayPssParams from_h(float h) {
    RayPssParams p;
    p.projection = ProjectionParams::from_h(h, PlaneFitMethod::wls);
    p.ball_radius = h;
    p.ball_spacing = 0.5f * p.ball_radius;
    p.epsilon = 1e-3f * h;
    p.max_candidates = 32;
    p.secondary_offset = 0.5f * h;
    return p;
  }
};

// How far (in h) a dropped sample may lie off the kept polynomial that stands for it: well
// inside the sheet a ray's candidate comes from, and below the offset between the two faces
// of the thin parts of a scan, whose polynomials must both stay (docs/paper-notes.md).
inline constexpr float kThinningTolerance = 0.05f;

// `--iterations auto`: projections repeat until |γ − r| < ε, up to this many.
inline constexpr int kAutoIterations = 32;

// The most ball intersections `--candidates` lets a ray try (each a BVH walk and up to
// --iterations projections): bounds a frame's time.
inline constexpr int kMaxCandidates = 1024;

// What a kernel sees of a prepared cloud: the grid for the range queries of the
// projection, the BVH over the balls, the local polynomials in BVH order and, for
// `--color`, the samples' colours.
struct PointSurfaceView {
  SupportGridView grid;
  BvhView bvh;
  const LocalPolynomial* locals = nullptr;  // locals[k] belongs to BVH primitive k
  const vec3* colors = nullptr;  // linear RGB of the grid's sorted samples; null: the shading's albedo
  RayPssParams params;
};

struct LocalHit {
  float t = kInfinity;
  int local = -1;  // index into PointSurfaceView::locals; -1 when none
};

// The ray's crossings of the local polynomial g of `lp` inside its ball B(p_i, b_i), in
// (t_min, t_max), nearest first: how many (0–2) are written to `ts` (paper §5.2,
// "Intersection"). Every search for local hits runs this one test. `margin` widens the slab
// by the rounding of the ray origin's coordinates (coordinate_rounding), which z0 and
// ray.at(lo) below carry; lp.height holds the sample's part.
PSS_INLINE int local_crossings(const LocalPolynomial& lp, const Ray& ray, float margin, float t_min, float t_max,
                               float ts[2]) {
  float t0, t1;
  if (!ray_ball(ray, lp.origin, lp.radius, t0, t1)) return 0;
  // Plain comparisons: fminf/fmaxf are library calls here, and NaN cannot occur. The
  // interval starts at the ball's entry whatever t_min is, so that a crossing found again by
  // the walk from it (the next batch) comes out the same float, which t_min then excludes.
  float lo = t0;
  float hi = t1 < t_max ? t1 : t_max;
  if (!(t_min < hi && lo < hi)) return 0;
  // Clip to the slab |z| ≤ height that holds the graph inside the ball.
  const float z0 = glm::dot(ray.origin - lp.origin, lp.normal);
  const float dz = glm::dot(ray.dir, lp.normal);
  const float height = lp.height + margin;
  if (dz != 0) {
    const float inv_dz = 1.0f / dz;
    const float ta = (-height - z0) * inv_dz, tb = (height - z0) * inv_dz;
    const float enter = ta < tb ? ta : tb, exit = ta < tb ? tb : ta;
    lo = enter > lo ? enter : lo;
    hi = exit < hi ? exit : hi;
    if (!(lo <= hi && t_min < hi)) return 0;
  } else if (abs(z0) > height) {
    return 0;
  }
  // Intersect from the ball's entry point, in the sample's frame: coordinates of order b
  // keep the quadratic's coefficients well scaled however far the camera is.
  const Frame frame = lp.frame();
  const vec3 o = frame.to_local(ray.at(lo));
  const vec3 d = frame.direction_to_local(ray.dir);
  // Most of the balls a ray meets after its first hit cross it farther on: refuse them
  // before solving (graph_crossed is exact up to rounding at the interval's ends).
  if (!graph_crossed(lp.g, o, d, hi - lo)) return 0;
  float roots[2];
  const int n = intersect_graph(lp.g, o, d, roots);  // ascending
  int count = 0;
  for (int i = 0; i < n; ++i) {
    const float t = lo + roots[i];
    if (t > t_min && t >= lo && t <= hi && t < t_max) ts[count++] = t;
  }
  return count;
}

// The nearest intersection with t in (t_min, t_max) of the ray and a local polynomial g_i,
// restricted to its ball, found through the BVH.
PSS_INLINE LocalHit nearest_local_hit(const PointSurfaceView& s, const Ray& ray, float t_min, float t_max) {
  LocalHit best;
  best.t = t_max;
  const float margin = coordinate_rounding(ray.origin);
  s.bvh.closest(ray, t_min, best.t, [&](int k, float& t_best) {
    float ts[2];
    if (local_crossings(s.locals[k], ray, margin, t_min, t_best, ts) == 0) return;
    t_best = ts[0];
    best.local = k;
  });
  if (best.local < 0) best.t = kInfinity;
  return best;
}

// The next few crossings of the ray with local polynomials beyond t_min, nearest first, from
// one walk of the BVH. A ray grazing the surface tries many candidates, each rejected after
// a projection; walking the BVH from its root for each was the longest chain of dependent
// steps in a GPU frame (docs/benchmarks.md, issue 29). The walk prunes at the batch's last
// crossing instead of its first, which costs little: the crossings near a ray's first one
// come from the same few balls.
struct LocalHitBatch {
  static constexpr int kSize = 4;
  float t[kSize];
  int local[kSize];
  int count = 0;
  bool complete = false;  // no crossing beyond t[count − 1] was left out
};

PSS_INLINE LocalHitBatch nearest_local_hits(const PointSurfaceView& s, const Ray& ray, float t_min, float t_max) {
  LocalHitBatch batch;
  float bound = t_max;
  const float margin = coordinate_rounding(ray.origin);
  const auto add = [&](float t, int k) {  // t < bound: insert, sorted, dropping the farthest
    int i = batch.count < LocalHitBatch::kSize ? batch.count++ : LocalHitBatch::kSize - 1;
    for (; i > 0 && batch.t[i - 1] > t; --i) {
      batch.t[i] = batch.t[i - 1];
      batch.local[i] = batch.local[i - 1];
    }
    batch.t[i] = t;
    batch.local[i] = k;
    if (batch.count == LocalHitBatch::kSize) bound = batch.t[LocalHitBatch::kSize - 1];
  };
  // `bound` is the walk's t_max (closest() takes it by reference): add() lowers it.
  s.bvh.closest(ray, t_min, bound, [&](int k, float&) {
    float ts[2];
    const int n = local_crossings(s.locals[k], ray, margin, t_min, bound, ts);
    if (n > 0) add(ts[0], k);  // (a double root once)
    if (n > 1 && ts[1] > ts[0] && ts[1] < bound) add(ts[1], k);  // a second crossing of the same graph
  });
  batch.complete = batch.count < LocalHitBatch::kSize;
  return batch;
}

// A rough hit, the paper's choice for secondary rays: the local polynomial's point and
// normal, no projection.
PSS_INLINE Hit rough_hit(const PointSurfaceView& s, const Ray& ray, float t_min, float t_max) {
  Hit hit;
  const LocalHit c = nearest_local_hit(s, ray, t_min, t_max);
  if (c.local < 0) return hit;
  const LocalPolynomial& lp = s.locals[c.local];
  hit.t = c.t;
  hit.point = ray.at(c.t);
  const Frame frame = lp.frame();
  const vec3 l = frame.to_local(hit.point);
  hit.normal = frame.direction_to_world(lp.g.normal(l.x, l.y));
  hit.scale = lp.radius / s.params.ball_radius;
  hit.flags = kHitFound | kHitRough;
  return hit;
}

// One candidate of paper §5.2's intersection (see the file comment): from the crossing `c`
// of a local polynomial, projections and intersections with the projections' polynomials
// until one converges (true: `hit` is it) or leaves the candidate's ball. `max_iterations`
// caps the projections; when the cap is reached the last ray/polynomial intersection is the
// hit, as after the paper's last rendering pass. hit.iterations counts the projections.
PSS_INLINE bool candidate_hit(const PointSurfaceView& s, const Ray& ray, LocalHit c, float t_min, float t_max,
                              int max_iterations, Hit& hit) {
  const RayPssParams& prm = s.params;
  const LocalPolynomial& lp = s.locals[c.local];
  const float b2 = lp.radius * lp.radius;
  hit.scale = lp.radius / prm.ball_radius;  // the sample's h_i/h
  const float epsilon = prm.epsilon * hit.scale;
  float t = c.t;
  vec3 hint = lp.normal;
  for (int it = 1;; ++it) {
    const vec3 r = ray.at(t);
    // Whether P(r) lies among its samples matters where r becomes the hit: within ε, or
    // at the last iteration.
    const Projection p =
        project_onto_surface(s.grid, r, prm.projection, hint, it >= max_iterations ? kInfinity : epsilon);
    ++hit.iterations;
    if (p.status == ProjectionStatus::too_few_neighbours) return false;
    // APSS's and RIMLS's fits without a surface leave r where it was: no hit (MLS's plane
    // through collinear samples still has its polynomial's point).
    if (p.status == ProjectionStatus::degenerate_normal && prm.projection.surface != SurfaceOperator::mls) return false;
    if (length2(p.point - r) < epsilon * epsilon) {
      if (!p.surrounded) return false;  // past the last samples (--borders clip)
      hit.t = t;
      hit.point = r;
      hit.normal = p.normal;  // g has no linear terms: n is the graph's normal at γ
      hit.flags = kHitFound | kHitConverged;
      return true;
    }
    // The ray against the new polynomial, from r in the projection's frame; the root
    // nearest r keeps the iteration on the same sheet of the surface.
    const vec3 o = p.frame.to_local(r);
    const vec3 d = p.frame.direction_to_local(ray.dir);
    float roots[2];
    const int n = intersect_graph(p.polynomial, o, d, roots);
    float step = kInfinity;
    for (int i = 0; i < n; ++i)
      if (t + roots[i] > t_min && t + roots[i] < t_max && abs(roots[i]) < abs(step)) step = roots[i];
    if (!(abs(step) < kInfinity)) return false;
    const float t_next = t + step;
    if (length2(ray.at(t_next) - lp.origin) > b2) return false;  // left B(p_i, b_i)
    t = t_next;
    hint = p.normal;
    if (it >= max_iterations) {
      if (!p.surrounded) return false;  // a capped hit past the last samples too
      hit.t = t;
      hit.point = ray.at(t);
      const vec3 l = p.frame.to_local(hit.point);
      hit.normal = p.frame.direction_to_world(p.polynomial.normal(l.x, l.y));
      hit.flags = kHitFound | kHitCapped;
      return true;
    }
  }
}

// The full intersection of paper §5.2: the candidates, nearest first, each tried in turn
// ("jump to the next ball" when one is rejected), up to max_candidates of them.
PSS_INLINE Hit intersect_pss(const PointSurfaceView& s, const Ray& ray, float t_min, float t_max,
                             int max_iterations) {
  Hit hit;
  LocalHitBatch next;
  int taken = 0;
  for (int candidate = 0; candidate < s.params.max_candidates; ++candidate) {
    if (taken == next.count) {  // the next batch, beyond the last
      if (next.complete) break;
      next = nearest_local_hits(s, ray, taken > 0 ? next.t[taken - 1] : t_min, t_max);
      taken = 0;
      if (next.count == 0) break;
    }
    if (candidate_hit(s, ray, LocalHit{next.t[taken], next.local[taken]}, t_min, t_max, max_iterations, hit)) return hit;
    ++taken;
  }
  return hit;
}

// What secondary rays use: the full loop or the paper's rough hit.
PSS_INLINE Hit intersect_secondary(const PointSurfaceView& s, const Ray& ray, float t_max, int max_iterations) {
  return s.params.secondary == SecondaryMode::full ? intersect_pss(s, ray, 0.0f, t_max, max_iterations)
                                                   : rough_hit(s, ray, 0.0f, t_max);
}

}  // namespace pss
