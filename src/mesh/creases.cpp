#include "creases.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <set>
#include <utility>

#include <glm/ext/matrix_double3x3.hpp>
#include <glm/geometric.hpp>

#include "incidence.hpp"
#include "pss/backend/cpu/parallel_for.hpp"

namespace pss::mesh_detail {

namespace {

// A patch's directions whose eigenvalue in Σ n nᵀ is below this share of the largest are
// left to the vertices' mean (dual contouring's truncated pseudo-inverse): its tangent
// planes do not fix the point along them. A crease of 30° between two equal halves gives
// about 0.07; noise in the normals of a flat patch, about 10⁻³.
constexpr double kPlaneRank = 0.02;

// A crease's tangent planes pass within this share of the cube's side of their meeting
// point, at root mean square: a box's scanned edges under RIMLS, 0.006 (median; 90 % within
// 0.017); where a smooth surface turns as far, 0.05-0.07 (the bunny's, the dragon's).
constexpr double kCreasePlanes = 0.02;

// A fan's centre keeps this share of the cube's side from its faces, as the edges' roots
// keep theirs from the corners (implicit_kernels.hpp: kEdgeMargin), so its triangles do
// not degenerate.
constexpr double kInside = 1e-2;

// The eigenvalues (ascending) and unit eigenvectors (columns) of a symmetric 3×3 matrix, by
// Jacobi's rotations.
std::pair<glm::dvec3, glm::dmat3> eigen(glm::dmat3 a) {
  glm::dmat3 v(1.0);
  for (int sweep = 0; sweep < 50; ++sweep) {
    const double off = a[0][1] * a[0][1] + a[0][2] * a[0][2] + a[1][2] * a[1][2];
    if (off <= 1e-30 * (a[0][0] * a[0][0] + a[1][1] * a[1][1] + a[2][2] * a[2][2]) || off == 0) break;
    for (int p = 0; p < 2; ++p)
      for (int q = p + 1; q < 3; ++q) {
        if (a[q][p] == 0) continue;
        const double theta = (a[q][q] - a[p][p]) / (2 * a[q][p]);
        const double t = (theta >= 0 ? 1.0 : -1.0) / (std::abs(theta) + std::sqrt(theta * theta + 1));
        const double c = 1 / std::sqrt(t * t + 1), s = t * c;
        glm::dmat3 r(1.0);  // rotation in the (p, q) plane: a ← rᵀ a r zeroes a[p][q]
        r[p][p] = c;
        r[q][q] = c;
        r[q][p] = s;
        r[p][q] = -s;
        a = glm::transpose(r) * a * r;
        v = v * r;
      }
  }
  std::array<int, 3> order{0, 1, 2};
  std::sort(order.begin(), order.end(), [&](int i, int j) { return a[i][i] < a[j][j]; });
  glm::dvec3 values;
  glm::dmat3 vectors;
  for (int k = 0; k < 3; ++k) {
    values[k] = a[order[k]][order[k]];
    vectors[k] = v[order[k]];
  }
  return {values, vectors};
}

// One cube's patch, and the fan that may replace it.
struct Fan {
  bool candidate = false;
  vec3 centre{0.0f}, normal{0.0f};
  std::vector<int> loop;  // the patch's boundary, in the triangles' direction
};

// The patch's boundary as one loop, when its triangles make one disk; else empty.
std::vector<int> boundary_loop(const std::array<int, 3>* triangles, std::size_t count) {
  std::vector<std::pair<int, int>> directed, boundary;
  for (std::size_t t = 0; t < count; ++t)
    for (int k = 0; k < 3; ++k) directed.push_back({triangles[t][k], triangles[t][(k + 1) % 3]});
  std::sort(directed.begin(), directed.end());
  std::vector<int> vertices;
  for (const auto& [u, v] : directed) {
    vertices.push_back(u);
    if (!std::binary_search(directed.begin(), directed.end(), std::pair{v, u})) boundary.push_back({u, v});
  }
  std::sort(vertices.begin(), vertices.end());
  vertices.erase(std::unique(vertices.begin(), vertices.end()), vertices.end());
  const std::size_t interior_edges = (directed.size() - boundary.size()) / 2;
  const auto euler = std::int64_t(vertices.size()) - std::int64_t(interior_edges + boundary.size()) +
                     std::int64_t(count);
  if (boundary.empty() || euler != 1) return {};
  std::vector<int> loop;  // boundary is sorted by its first vertex: follow it
  int at = boundary.front().first;
  for (std::size_t step = 0; step < boundary.size(); ++step) {
    const auto next = std::lower_bound(boundary.begin(), boundary.end(), std::pair{at, INT32_MIN});
    if (next == boundary.end() || next->first != at || (next + 1 != boundary.end() && (next + 1)->first == at))
      return {};
    loop.push_back(at);
    at = next->second;
  }
  return at == loop.front() ? loop : std::vector<int>{};
}

// Whether a fan from `centre` over `loop` may replace a cube's patch: the centre lies inside
// the cube (so the fan is embedded), and no triangle of the fan faces against the normals at
// its edge on the cube's faces.
bool fits(const TriangleMesh& mesh, const std::vector<int>& loop, glm::dvec3 centre, vec3 lowest, float cell) {
  const glm::dvec3 low = glm::dvec3(lowest) + kInside * cell, high = low + (1 - 2 * kInside) * cell;
  if (glm::any(glm::lessThan(centre, low)) || glm::any(glm::greaterThan(centre, high))) return false;
  for (std::size_t i = 0; i < loop.size(); ++i) {
    const auto u = std::size_t(loop[i]), v = std::size_t(loop[(i + 1) % loop.size()]);
    const glm::dvec3 pu(mesh.positions[u]), pv(mesh.positions[v]);
    const glm::dvec3 face = glm::cross(pv - pu, centre - pu);
    if (!(glm::dot(face, glm::dvec3(mesh.normals[u] + mesh.normals[v])) > 0)) return false;
  }
  return true;
}

// The vertices of cube c's triangles, sorted.
std::vector<int> patch_vertices(const TriangleMesh& mesh, const CubeTriangles& cubes, std::size_t c) {
  std::vector<int> patch;
  for (std::size_t t = cubes.first[c]; t < cubes.first[c + 1]; ++t)
    patch.insert(patch.end(), mesh.triangles[t].begin(), mesh.triangles[t].end());
  std::sort(patch.begin(), patch.end());
  patch.erase(std::unique(patch.begin(), patch.end()), patch.end());
  return patch;
}

// Cube c's fan, from the tangent planes at its vertices.
Fan fan_of(const TriangleMesh& mesh, const CubeTriangles& cubes, std::size_t c, float cell, double most_cos) {
  Fan fan;
  const std::vector<int> planes_at = patch_vertices(mesh, cubes, c);
  double least_cos = 1;
  for (std::size_t i = 0; i < planes_at.size(); ++i)
    for (std::size_t j = i + 1; j < planes_at.size(); ++j)
      least_cos = std::min(least_cos, double(glm::dot(mesh.normals[std::size_t(planes_at[i])],
                                                      mesh.normals[std::size_t(planes_at[j])])));
  if (least_cos >= most_cos) return fan;
  fan.loop = boundary_loop(mesh.triangles.data() + cubes.first[c], cubes.first[c + 1] - cubes.first[c]);
  if (fan.loop.empty()) return fan;

  // The point nearest the tangent planes, from the vertices' mean along the directions the
  // planes fix.
  glm::dvec3 mean(0.0), normal(0.0);
  for (const int v : planes_at) {
    mean += glm::dvec3(mesh.positions[std::size_t(v)]) / double(planes_at.size());
    normal += glm::dvec3(mesh.normals[std::size_t(v)]);
  }
  glm::dmat3 planes(0.0);
  glm::dvec3 rhs(0.0);
  for (const int v : planes_at) {
    const glm::dvec3 n(mesh.normals[std::size_t(v)]);
    planes += glm::outerProduct(n, n);
    rhs += n * glm::dot(n, glm::dvec3(mesh.positions[std::size_t(v)]) - mean);
  }
  const auto [values, vectors] = eigen(planes);
  glm::dvec3 centre = mean;
  for (int k = 0; k < 3; ++k)
    if (values[k] > kPlaneRank * values[2]) centre += vectors[k] * (glm::dot(vectors[k], rhs) / values[k]);
  const glm::dvec3 low = glm::dvec3(cubes.lowest[c]) + kInside * cell, high = low + (1 - 2 * kInside) * cell;
  // On a crease (two planes: the least eigenvalue's direction runs along it) the point is
  // any of a line's: the one inside the cube nearest the mean.
  if (values[0] <= kPlaneRank * values[2] && values[1] > kPlaneRank * values[2]) {
    const glm::dvec3 along = vectors[0];
    double first = -1e300, last = 1e300;  // the stretch of centre + t·along inside the cube
    for (int axis = 0; axis < 3; ++axis) {
      if (std::abs(along[axis]) < 1e-12) continue;
      const double t0 = (low[axis] - centre[axis]) / along[axis], t1 = (high[axis] - centre[axis]) / along[axis];
      first = std::max(first, std::min(t0, t1));
      last = std::min(last, std::max(t0, t1));
    }
    if (first <= last) centre += along * std::clamp(0.0, first, last);
  }
  if (!fits(mesh, fan.loop, centre, cubes.lowest[c], cell)) return fan;
  // The planes meet there: a curved surface's (its normals as far apart) pass it farther.
  double residual = 0;
  for (const int v : planes_at) {
    const glm::dvec3 n(mesh.normals[std::size_t(v)]), p(mesh.positions[std::size_t(v)]);
    const double off = glm::dot(n, centre - p);
    residual += off * off / double(planes_at.size());
  }
  if (!(std::sqrt(residual) <= kCreasePlanes * cell)) return fan;
  fan.candidate = true;
  fan.centre = vec3(centre);
  fan.normal = vec3(glm::normalize(normal));
  return fan;
}

// Flips each edge whose two triangles' third vertices are two fans' centres (index
// `first_centre` on), so the crease joins them, unless that edge exists or a new triangle
// would face against the old pair.
std::int64_t flip_between_centres(TriangleMesh& mesh, int first_centre, double most_cos) {
  const Incidence in = incidence(mesh.triangles);
  const auto& sides = in.sides;
  auto exists = [&](int a, int b) {
    const Side key{std::min(a, b), std::max(a, b), -1, false};
    const auto at = std::lower_bound(sides.begin(), sides.end(), key, [](const Side& x, const Side& y) {
      return x.low != y.low ? x.low < y.low : x.high < y.high;
    });
    return at != sides.end() && at->same_edge(key);
  };
  auto third = [&](std::int64_t t, int a, int b) {
    for (const int v : mesh.triangles[std::size_t(t)])
      if (v != a && v != b) return v;
    return a;
  };
  auto face = [&](int a, int b, int c) {
    const vec3 pa = mesh.positions[std::size_t(a)];
    return glm::dvec3(glm::cross(mesh.positions[std::size_t(b)] - pa, mesh.positions[std::size_t(c)] - pa));
  };
  std::vector<char> changed(mesh.triangles.size(), 0);
  std::set<std::pair<int, int>> made;
  std::int64_t flips = 0;
  for (std::size_t i = 0; i + 1 < sides.size(); ++i) {
    if (!sides[i].same_edge(sides[i + 1]) || (i + 2 < sides.size() && sides[i + 2].same_edge(sides[i]))) continue;
    if (i > 0 && sides[i - 1].same_edge(sides[i])) continue;
    const Side& s1 = sides[i].forward ? sides[i] : sides[i + 1];  // runs low → high
    const Side& s2 = sides[i].forward ? sides[i + 1] : sides[i];
    if (s1.forward == s2.forward || changed[std::size_t(s1.triangle)] || changed[std::size_t(s2.triangle)]) continue;
    const int a = s1.low, b = s1.high;
    const int c1 = third(s1.triangle, a, b), c2 = third(s2.triangle, a, b);
    if (c1 < first_centre || c2 < first_centre || c1 == c2) continue;
    // Only an edge across the crease (its ends' normals apart) stands between the centres.
    if (!(glm::dot(mesh.normals[std::size_t(a)], mesh.normals[std::size_t(b)]) < most_cos)) continue;
    if (exists(c1, c2) || made.count({std::min(c1, c2), std::max(c1, c2)})) continue;
    // (a, b, c1) and (b, a, c2) become (a, c2, c1) and (c2, b, c1).
    const glm::dvec3 old = face(a, b, c1) + face(b, a, c2);
    if (!(glm::dot(face(a, c2, c1), old) > 0) || !(glm::dot(face(c2, b, c1), old) > 0)) continue;
    mesh.triangles[std::size_t(s1.triangle)] = {a, c2, c1};
    mesh.triangles[std::size_t(s2.triangle)] = {c2, b, c1};
    changed[std::size_t(s1.triangle)] = changed[std::size_t(s2.triangle)] = 1;
    made.insert({std::min(c1, c2), std::max(c1, c2)});
    ++flips;
  }
  return flips;
}

}  // namespace

CreaseCounts snap_creases(TriangleMesh& mesh, CubeTriangles& cubes, float cell, const ImplicitSurface& implicit,
                          float crease_angle) {
  CreaseCounts counts;
  const std::size_t n = cubes.lowest.size();
  if (!(crease_angle < 180) || n == 0) return counts;
  const double most_cos = std::cos(double(crease_angle) * M_PI / 180);
  std::vector<Fan> fans(n);
  cpu::parallel_for(std::int64_t(n), [&](std::int64_t i) {
    const std::size_t c = std::size_t(i);
    fans[c] = fan_of(mesh, cubes, c, cell, most_cos);
  });
  // The candidates' centres on the surface, in one batch.
  std::vector<std::size_t> candidates;
  for (std::size_t c = 0; c < n; ++c)
    if (fans[c].candidate) candidates.push_back(c);
  std::vector<vec3> centres(candidates.size());
  for (std::size_t k = 0; k < candidates.size(); ++k) centres[k] = fans[candidates[k]].centre;
  std::vector<CornerSample> at(candidates.size());
  if (!centres.empty()) {
    Progress progress("mesh creases", std::int64_t(centres.size()));
    implicit.sample(centres, at, progress);
  }
  // A centre on a crease lies on the surface; it moves onto it, as every vertex, unless that
  // takes it out of its cube (it is then nearer than the tolerance already).
  for (std::size_t k = 0; k < candidates.size(); ++k) {
    Fan& fan = fans[candidates[k]];
    fan.candidate = at[k].valid && std::abs(at[k].distance) <= kCreaseOnSurface * cell;
    if (at[k].on_surface && fits(mesh, fan.loop, glm::dvec3(at[k].surface_point), cubes.lowest[candidates[k]], cell))
      fan.centre = at[k].surface_point;
  }

  const int first_centre = int(mesh.positions.size());
  std::vector<std::array<int, 3>> triangles;
  triangles.reserve(mesh.triangles.size());
  std::vector<std::size_t> first(n + 1, 0);
  for (std::size_t c = 0; c < n; ++c) {
    const Fan& fan = fans[c];
    first[c] = triangles.size();
    if (!fan.candidate) {
      triangles.insert(triangles.end(), mesh.triangles.begin() + std::ptrdiff_t(cubes.first[c]),
                       mesh.triangles.begin() + std::ptrdiff_t(cubes.first[c + 1]));
      continue;
    }
    const int centre = int(mesh.positions.size());
    mesh.positions.push_back(fan.centre);
    mesh.normals.push_back(fan.normal);
    cubes.centres.push_back(c);
    for (std::size_t i = 0; i < fan.loop.size(); ++i)
      triangles.push_back({fan.loop[i], fan.loop[(i + 1) % fan.loop.size()], centre});
    ++counts.vertices;
  }
  first[n] = triangles.size();
  cubes.first.swap(first);
  mesh.triangles.swap(triangles);
  if (counts.vertices > 0) counts.flips = flip_between_centres(mesh, first_centre, most_cos);
  return counts;
}

}  // namespace pss::mesh_detail
