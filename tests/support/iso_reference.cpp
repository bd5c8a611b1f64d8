// See iso_reference.hpp. Everything above "pss's volume method" reads only the voxels.
#include "support/iso_reference.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "pss/backend/cpu/parallel_for.hpp"
#include "pss/render/rendered_frame.hpp"
#include "pss/render/shading.hpp"
#include "pss/volume/render_volume.hpp"

namespace pss::test {

namespace {

// The 8 corner values of cell (i, j, k), corner c at (i + (c & 1), j + (c >> 1 & 1), k + (c >> 2)).
struct Corners {
  float x[8];
  float lo, hi;
};

Corners corners_of(const VolumeView& v, ivec3 cell) {
  Corners c;
  const std::int64_t dj = v.dims.x, dk = std::int64_t(v.dims.x) * v.dims.y;
  const float* base = v.values + v.index(cell.x, cell.y, cell.z);
  const std::int64_t offsets[8] = {0, 1, dj, dj + 1, dk, dk + 1, dk + dj, dk + dj + 1};
  c.lo = kInfinity;
  c.hi = -kInfinity;
  for (int n = 0; n < 8; ++n) {
    c.x[n] = base[offsets[n]];
    c.lo = std::fmin(c.lo, c.x[n]);
    c.hi = std::fmax(c.hi, c.x[n]);
  }
  return c;
}

// The trilinear interpolant of a cell at fractions f (slightly outside [0, 1] extrapolates).
float interpolate(const float x[8], vec3 f) {
  const float c00 = x[0] + f.x * (x[1] - x[0]), c10 = x[2] + f.x * (x[3] - x[2]);
  const float c01 = x[4] + f.x * (x[5] - x[4]), c11 = x[6] + f.x * (x[7] - x[6]);
  const float c0 = c00 + f.y * (c10 - c00), c1 = c01 + f.y * (c11 - c01);
  return c0 + f.z * (c1 - c0);
}

// Its gradient in value per grid unit.
vec3 interpolant_gradient(const float x[8], vec3 f) {
  const auto lerp = [](float a, float b, float w) { return a + w * (b - a); };
  const float dx = lerp(lerp(x[1] - x[0], x[3] - x[2], f.y), lerp(x[5] - x[4], x[7] - x[6], f.y), f.z);
  const float dy = lerp(lerp(x[2] - x[0], x[3] - x[1], f.x), lerp(x[6] - x[4], x[7] - x[5], f.x), f.z);
  const float dz = lerp(lerp(x[4] - x[0], x[5] - x[1], f.x), lerp(x[6] - x[2], x[7] - x[3], f.x), f.y);
  return vec3(dx, dy, dz);
}

// The central-difference gradient (world units) interpolated trilinearly in the cell;
// the interpolant's own gradient where that vanishes.
vec3 reference_normal(const VolumeView& v, ivec3 cell, vec3 f, const float x[8], vec3 ray_dir) {
  vec3 g(0.0f);
  for (int n = 0; n < 8; ++n) {
    const int a = n & 1, b = n >> 1 & 1, c = n >> 2;
    const float w = (a ? f.x : 1 - f.x) * (b ? f.y : 1 - f.y) * (c ? f.z : 1 - f.z);
    g += w * central_difference(v, cell.x + a, cell.y + b, cell.z + c);
  }
  if (!(length2(g) > 0)) g = interpolant_gradient(x, f) / v.spacing;
  if (!(length2(g) > 0)) return -ray_dir;
  return glm::normalize(g);
}

}  // namespace

ReferencePixel cast_iso_ray(const VolumeView& v, float iso, const Ray& ray, int steps_per_voxel) {
  ReferencePixel out;
  if (v.dims.x < 2 || v.dims.y < 2 || v.dims.z < 2) return out;
  // Walk in continuous grid coordinates, where cells are unit cubes.
  const vec3 go = v.to_grid(ray.origin), gd = ray.dir / v.spacing;
  const vec3 top(float(v.dims.x - 1), float(v.dims.y - 1), float(v.dims.z - 1));
  float t0 = 0, t1 = kInfinity;
  for (int a = 0; a < 3; ++a) {
    if (gd[a] == 0) {
      if (go[a] < 0 || go[a] > top[a]) return out;
      continue;
    }
    float ta = -go[a] / gd[a], tb = (top[a] - go[a]) / gd[a];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
  }
  if (!(t0 <= t1)) return out;

  const ivec3 last = v.dims - 2;
  const vec3 g0 = go + t0 * gd;
  ivec3 cell;
  ivec3 step;
  vec3 t_next, t_delta;
  for (int a = 0; a < 3; ++a) {
    cell[a] = clamp(int(std::floor(g0[a])), 0, last[a]);
    if (gd[a] > 0) {
      step[a] = 1;
      t_next[a] = (float(cell[a] + 1) - go[a]) / gd[a];
      t_delta[a] = 1 / gd[a];
    } else if (gd[a] < 0) {
      step[a] = -1;
      t_next[a] = (float(cell[a]) - go[a]) / gd[a];
      t_delta[a] = -1 / gd[a];
    } else {
      step[a] = 0;
      t_next[a] = kInfinity;
      t_delta[a] = kInfinity;
    }
  }
  const float grid_speed = glm::length(gd);  // grid units per unit of t
  const auto fractions = [&](float t) { return go + t * gd - vec3(cell); };

  float t_enter = t0;
  bool above = false;
  bool first = true;
  for (;;) {
    const float t_exit = std::min(std::min(t_next.x, t_next.y), std::min(t_next.z, t1));
    const Corners c = corners_of(v, cell);
    if (first) {
      // The side the ray enters on; a box face is never a crossing.
      above = interpolate(c.x, fractions(t0)) > iso;
      first = false;
    }
    if (c.lo <= iso && iso < c.hi) {
      const int n = std::max(1, int(std::ceil((t_exit - t_enter) * grid_speed * float(steps_per_voxel))));
      const float dt = (t_exit - t_enter) / float(n);
      float ta = t_enter;
      for (int m = 1; m <= n; ++m) {
        const float tb = m == n ? t_exit : t_enter + float(m) * dt;
        if ((interpolate(c.x, fractions(tb)) > iso) != above) {
          // Bisect [ta, tb]: ta on the `above` side, tb across.
          float lo = ta, hi = tb;
          for (int it = 0; it < 30 && hi - lo > 0; ++it) {
            const float mid = 0.5f * (lo + hi);
            if (mid <= lo || mid >= hi) break;
            if ((interpolate(c.x, fractions(mid)) > iso) == above)
              lo = mid;
            else
              hi = mid;
          }
          out.found = true;
          out.t = 0.5f * (lo + hi);
          out.point = ray.at(out.t);
          out.normal = reference_normal(v, cell, glm::clamp(fractions(out.t), vec3(0.0f), vec3(1.0f)), c.x, ray.dir);
          return out;
        }
        ta = tb;
      }
    } else {
      above = c.lo > iso;  // the whole cell is on one side
    }
    if (t_exit >= t1) break;
    const int a = t_next.x <= t_next.y ? (t_next.x <= t_next.z ? 0 : 2) : (t_next.y <= t_next.z ? 1 : 2);
    cell[a] += step[a];
    if (cell[a] < 0 || cell[a] > last[a]) break;
    t_enter = t_next[a];
    t_next[a] += t_delta[a];
  }
  return out;
}

ReferenceImage cast_iso_reference(const VolumeView& v, float iso, const Camera& camera, int steps_per_voxel) {
  ReferenceImage image;
  image.width = camera.width;
  image.height = camera.height;
  const std::int64_t n = std::int64_t(camera.width) * camera.height;
  image.pixels.resize(std::size_t(n));
  cpu::parallel_for(n, [&](std::int64_t i) {
    image.pixels[std::size_t(i)] =
        cast_iso_ray(v, iso, camera.primary_ray(int(i % camera.width), int(i / camera.width)), steps_per_voxel);
  });
  return image;
}

namespace {

float point_segment_distance2(vec3 p, vec3 a, vec3 b) {
  const vec3 ab = b - a;
  const float l2 = length2(ab);
  const float s = l2 > 0 ? clamp(glm::dot(p - a, ab) / l2, 0.0f, 1.0f) : 0.0f;
  return length2(p - (a + s * ab));
}

float point_triangle_distance2(vec3 p, const Triangle& t) {
  const vec3 a = t.a, b = t.b, c = t.c;
  const vec3 ab = b - a, ac = c - a, ap = p - a;
  const float d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) return length2(ap);
  const vec3 bp = p - b;
  const float d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return length2(bp);
  const float vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return length2(p - (a + d1 / (d1 - d3) * ab));
  const vec3 cp = p - c;
  const float d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return length2(cp);
  const float vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return length2(p - (a + d2 / (d2 - d6) * ac));
  const float va = d3 * d6 - d5 * d4;
  if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0)
    return length2(p - (b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b)));
  const float sum = va + vb + vc;
  if (!(sum > 0)) {
    // A degenerate (zero-area) triangle: marching tetrahedra makes them where the surface
    // passes through a voxel. Its distance is that of its edges.
    return std::min({point_segment_distance2(p, a, b), point_segment_distance2(p, b, c),
                     point_segment_distance2(p, c, a)});
  }
  return length2(p - (a + (vb / sum) * ab + (vc / sum) * ac));
}

}  // namespace

float point_triangle_distance(vec3 p, const Triangle& t) { return std::sqrt(point_triangle_distance2(p, t)); }

ReferenceMesh::ReferenceMesh(const VolumeView& v, float iso)
    : ReferenceMesh(marching_tetrahedra_triangles(v, iso), 2 * v.voxel_size()) {}

ReferenceMesh::ReferenceMesh(std::vector<Triangle> triangles, float cell_size)
    : triangles_(std::move(triangles)), cell_(cell_size) {
  if (triangles_.empty()) return;
  Aabb box;
  for (const Triangle& t : triangles_) {
    box.grow(t.a);
    box.grow(t.b);
    box.grow(t.c);
  }
  lo_ = box.lo;
  for (int a = 0; a < 3; ++a) cells_[a] = std::max(1, int(std::floor(box.extent()[a] / cell_)) + 1);
  const auto cell_range = [&](const Triangle& t, ivec3& c0, ivec3& c1) {
    const vec3 lo = glm::min(t.a, glm::min(t.b, t.c)), hi = glm::max(t.a, glm::max(t.b, t.c));
    for (int a = 0; a < 3; ++a) {
      c0[a] = clamp(int(std::floor((lo[a] - lo_[a]) / cell_)), 0, cells_[a] - 1);
      c1[a] = clamp(int(std::floor((hi[a] - lo_[a]) / cell_)), 0, cells_[a] - 1);
    }
  };
  const auto index = [&](int x, int y, int z) { return (std::int64_t(z) * cells_.y + y) * cells_.x + x; };
  start_.assign(std::size_t(std::int64_t(cells_.x) * cells_.y * cells_.z + 1), 0);
  for (const Triangle& t : triangles_) {
    ivec3 c0, c1;
    cell_range(t, c0, c1);
    for (int z = c0.z; z <= c1.z; ++z)
      for (int y = c0.y; y <= c1.y; ++y)
        for (int x = c0.x; x <= c1.x; ++x) ++start_[std::size_t(index(x, y, z) + 1)];
  }
  for (std::size_t c = 1; c < start_.size(); ++c) start_[c] += start_[c - 1];
  items_.resize(std::size_t(start_.back()));
  std::vector<std::int64_t> fill(start_.begin(), start_.end() - 1);
  for (std::size_t i = 0; i < triangles_.size(); ++i) {
    ivec3 c0, c1;
    cell_range(triangles_[i], c0, c1);
    for (int z = c0.z; z <= c1.z; ++z)
      for (int y = c0.y; y <= c1.y; ++y)
        for (int x = c0.x; x <= c1.x; ++x) items_[std::size_t(fill[std::size_t(index(x, y, z))]++)] = std::int32_t(i);
  }
}

float ReferenceMesh::distance(vec3 p) const {
  if (triangles_.empty()) return kInfinity;
  const vec3 g = glm::clamp((p - lo_) / cell_, vec3(-1e7f), vec3(1e7f));
  const ivec3 c(int(std::floor(g.x)), int(std::floor(g.y)), int(std::floor(g.z)));
  // Rings nearer than the grid hold no cells.
  int r = 0;
  for (int a = 0; a < 3; ++a) r = std::max({r, -c[a], c[a] - (cells_[a] - 1)});
  float best2 = kInfinity;
  const auto visit = [&](int x, int y, int z) {
    const std::int64_t cell = (std::int64_t(z) * cells_.y + y) * cells_.x + x;
    for (std::int64_t n = start_[std::size_t(cell)]; n < start_[std::size_t(cell) + 1]; ++n)
      best2 = std::min(best2, point_triangle_distance2(p, triangles_[std::size_t(items_[std::size_t(n)])]));
  };
  for (;; ++r) {
    const ivec3 lo = glm::max(c - r, ivec3(0)), hi = glm::min(c + r, cells_ - 1);
    for (int z = lo.z; z <= hi.z; ++z)
      for (int y = lo.y; y <= hi.y; ++y) {
        if (std::abs(z - c.z) == r || std::abs(y - c.y) == r) {
          for (int x = lo.x; x <= hi.x; ++x) visit(x, y, z);
        } else {
          if (c.x - r >= lo.x && c.x - r <= hi.x) visit(c.x - r, y, z);
          if (r > 0 && c.x + r >= lo.x && c.x + r <= hi.x) visit(c.x + r, y, z);
        }
      }
    // Every triangle nearer than the boundary of the box of rings 0..r has been seen.
    float inner = kInfinity;
    for (int a = 0; a < 3; ++a)
      inner = std::min({inner, g[a] - float(c[a] - r), float(c[a] + r + 1) - g[a]});
    inner *= cell_;
    if (inner > 0 && best2 <= inner * inner) break;
    if (c.x - r <= 0 && c.y - r <= 0 && c.z - r <= 0 && c.x + r >= cells_.x - 1 && c.y + r >= cells_.y - 1 &&
        c.z + r >= cells_.z - 1)
      break;  // the whole grid
  }
  return std::sqrt(best2);
}

float ReferenceMesh::distance_brute_force(vec3 p) const {
  float best2 = kInfinity;
  for (const Triangle& t : triangles_) best2 = std::min(best2, point_triangle_distance2(p, t));
  return std::sqrt(best2);
}

ReferenceComparison compare_to_reference(const std::vector<Hit>& hits, const ReferenceImage& ref,
                                         const ReferenceMesh& mesh, float voxel) {
  ReferenceComparison r;
  const std::size_t n = std::min(hits.size(), ref.pixels.size());
  std::vector<float> distance(n, -1.0f);
  cpu::parallel_for(std::int64_t(n), [&](std::int64_t i) {
    if (hits[std::size_t(i)].found()) distance[std::size_t(i)] = mesh.distance(hits[std::size_t(i)].point) / voxel;
  });
  std::vector<float> d;
  double depth = 0, angle = 0;
  std::int64_t both = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const bool pss = hits[i].found(), reference = ref.pixels[i].found;
    r.object_pixels += reference;
    r.hole_pixels += reference && !pss;
    r.phantom_pixels += pss && !reference;
    if (pss) d.push_back(distance[i]);
    if (pss && reference) {
      ++both;
      depth += glm::length(hits[i].point - ref.pixels[i].point) / voxel;
      const float ahead = (ref.pixels[i].t - hits[i].t) / voxel;
      r.in_front_pixels += ahead > 1;
      r.behind_pixels += ahead < -1;
      const float cos = std::abs(glm::dot(glm::normalize(hits[i].normal), ref.pixels[i].normal));
      angle += std::acos(std::min(1.0f, cos)) * 57.2957795;
    }
  }
  // 8-neighbourhood counts of reference hits, for the rim-tolerant figures.
  const int w = ref.width, h = ref.height;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const std::size_t i = std::size_t(y) * w + x;
      if (i >= n || hits[i].found() == ref.pixels[i].found) continue;
      int around = 0, inside = 0;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          if ((dx == 0 && dy == 0) || x + dx < 0 || y + dy < 0 || x + dx >= w || y + dy >= h) continue;
          ++around;
          inside += ref.pixels[std::size_t(y + dy) * w + x + dx].found;
        }
      r.interior_hole_pixels += ref.pixels[i].found && inside == around;
      r.exterior_phantom_pixels += hits[i].found() && inside == 0;
    }
  r.pss_hits = std::int64_t(d.size());
  if (r.object_pixels) {
    r.interior_holes = double(r.interior_hole_pixels) / double(r.object_pixels);
    r.exterior_phantom = double(r.exterior_phantom_pixels) / double(r.object_pixels);
    r.holes = double(r.hole_pixels) / double(r.object_pixels);
    r.phantom = double(r.phantom_pixels) / double(r.object_pixels);
    r.in_front = double(r.in_front_pixels) / double(r.object_pixels);
    r.behind = double(r.behind_pixels) / double(r.object_pixels);
  }
  if (!d.empty()) {
    double sum = 0;
    for (float x : d) sum += x;
    r.mean_distance = sum / double(d.size());
    const std::size_t k = std::size_t(std::ceil(0.99 * double(d.size()))) - 1;
    std::nth_element(d.begin(), d.begin() + std::ptrdiff_t(k), d.end());
    r.p99_distance = d[k];
    r.max_distance = *std::max_element(d.begin(), d.end());
  }
  if (both) {
    r.mean_depth_difference = depth / double(both);
    r.mean_normal_angle_deg = angle / double(both);
  }
  return r;
}

std::vector<vec3> shade_reference(const ReferenceImage& ref, const Camera& camera) {
  std::vector<vec3> out(ref.pixels.size(), vec3(0.0f));
  for (std::size_t i = 0; i < ref.pixels.size(); ++i) {
    const ReferencePixel& p = ref.pixels[i];
    if (!p.found) continue;
    const vec3 dir = camera.primary_ray(int(i % std::size_t(ref.width)), int(i / std::size_t(ref.width))).dir;
    out[i] = vec3(0.05f + 0.75f * std::abs(glm::dot(p.normal, dir)));
  }
  return out;
}

std::vector<vec3> disagreement_image(const std::vector<Hit>& hits, const ReferenceImage& ref, const Camera& camera,
                                     float voxel) {
  std::vector<vec3> out = shade_reference(ref, camera);
  for (std::size_t i = 0; i < out.size() && i < hits.size(); ++i) {
    const bool pss = hits[i].found(), reference = ref.pixels[i].found;
    const float ahead = pss && reference ? (ref.pixels[i].t - hits[i].t) / voxel : 0.0f;
    if ((pss && !reference) || ahead > 1) out[i] = vec3(0.9f, 0.1f, 0.05f);
    if ((reference && !pss) || ahead < -1) out[i] = vec3(0.05f, 0.2f, 0.9f);
  }
  return out;
}

// --- pss's volume method: the only calls into it. ---

Camera volume_camera(const Aabb& box, int width, int height, float azimuth_deg, float elevation_deg) {
  CameraSettings s;  // the defaults of `pss volume`'s render options
  s.width = width;
  s.height = height;
  s.azimuth_deg = azimuth_deg;
  s.elevation_deg = elevation_deg;
  return Camera::framing(box, s);
}

RenderedFrame render_pss(const PreparedVolume& volume, const Camera& camera, double* frame_seconds) {
  TraceSettings settings;  // `pss volume` without --shadows / --reflections
  settings.shading = ShadingParams::for_camera(camera);
  Stats stats;
  RenderedFrame frame = render_volume(volume, camera, settings, Backend::cpu, stats);
  if (frame_seconds) *frame_seconds = stats.time("primary") + stats.time("secondary") + stats.time("shading");
  return frame;
}

ReferenceMeasurement measure_against_reference(const PreparedVolume& volume, float iso, const Camera& camera,
                                               const ReferenceMesh& mesh) {
  ReferenceMeasurement m;
  RenderedFrame frame = render_pss(volume, camera, &m.pss_seconds);
  const VolumeView v = volume.fields.volume.view();
  const auto start = std::chrono::steady_clock::now();
  m.reference = cast_iso_reference(v, iso, camera);
  m.reference_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  m.comparison = compare_to_reference(frame.hits, m.reference, mesh, v.voxel_size());
  m.hits = std::move(frame.hits);
  m.pss_image = std::move(frame.image.pixels);
  return m;
}

}  // namespace pss::test
