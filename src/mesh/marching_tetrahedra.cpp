#include "pss/mesh/marching_tetrahedra.hpp"

#include <algorithm>
#include <bit>
#include <array>
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>
#include <utility>

#include "creases.hpp"
#include "incidence.hpp"
#include "pss/backend/cpu/parallel_for.hpp"
#include "pss/core/error.hpp"
#include "pss/core/memory.hpp"

namespace pss {

namespace {

// Cube corner c (0..7) lies at offset (c & 1, c >> 1 & 1, c >> 2 & 1). Kuhn's six
// tetrahedra run from corner 0 to corner 7 along the cube's edges, one per order of the
// axes: any two of a tetrahedron's corners differ by a 0/1 offset, the later's bits a
// superset of the earlier's, so an edge is its lower corner and a direction 1..7.
constexpr int kTetrahedra[6][4] = {{0, 1, 3, 7}, {0, 1, 5, 7}, {0, 2, 3, 7}, {0, 2, 6, 7}, {0, 4, 5, 7}, {0, 4, 6, 7}};

ivec3 offset(int corner) { return ivec3(corner & 1, (corner >> 1) & 1, (corner >> 2) & 1); }

using Edge = std::array<int, 2>;  // two cube corners, the lower first
struct Case {
  int triangles = 0;
  std::array<std::array<Edge, 3>, 2> triangle{};
};

// The triangles of each tetrahedron for each set of negative corners (bit i: its corner i),
// ordered counter-clockwise seen from the positive side. The order is fixed wherever the
// vertices lie strictly inside their edges (a triangle of the split cannot degenerate
// there), so it is found once with every vertex at its edge's midpoint.
struct CaseTable {
  Case at[6][16];
  CaseTable() {
    for (int t = 0; t < 6; ++t)
      for (int mask = 0; mask < 16; ++mask) at[t][mask] = make(kTetrahedra[t], mask);
  }
  static Case make(const int (&tet)[4], int mask) {
    int negative[4], positive[4], nn = 0, np = 0;
    for (int i = 0; i < 4; ++i) (mask >> i & 1 ? negative[nn++] : positive[np++]) = tet[i];
    Case c;
    auto edge = [](int x, int y) { return x < y ? Edge{x, y} : Edge{y, x}; };
    if (nn == 1 || nn == 3) {
      const int lone = nn == 1 ? negative[0] : positive[0];
      const int* rest = nn == 1 ? positive : negative;
      c.triangles = 1;
      c.triangle[0] = {edge(lone, rest[0]), edge(lone, rest[1]), edge(lone, rest[2])};
    } else if (nn == 2) {
      const int a = negative[0], b = negative[1], p = positive[0], q = positive[1];
      c.triangles = 2;  // the quad a-p, a-q, b-q, b-p
      c.triangle[0] = {edge(a, p), edge(a, q), edge(b, q)};
      c.triangle[1] = {edge(a, p), edge(b, q), edge(b, p)};
    }
    glm::dvec3 outward(0.0);  // from the negative corners' mean to the positive's
    for (int i = 0; i < np; ++i) outward += glm::dvec3(offset(positive[i])) / double(np);
    for (int i = 0; i < nn; ++i) outward -= glm::dvec3(offset(negative[i])) / double(nn);
    for (int k = 0; k < c.triangles; ++k) {
      auto mid = [&](int v) { return 0.5 * glm::dvec3(offset(c.triangle[k][v][0]) + offset(c.triangle[k][v][1])); };
      const glm::dvec3 normal = glm::cross(mid(1) - mid(0), mid(2) - mid(0));
      if (glm::dot(normal, outward) < 0) std::swap(c.triangle[k][1], c.triangle[k][2]);
    }
    return c;
  }
};
const CaseTable kCases;

std::uint64_t edge_key(ivec3 cube, Edge e) {
  return Lattice::key(cube + offset(e[0])) << 3 | std::uint64_t(e[1] & ~e[0]);
}

// Sorted, unique keys, and those of `add` not in `have`.
std::vector<std::uint64_t> unique_sorted(std::vector<std::uint64_t> keys) {
  std::sort(keys.begin(), keys.end());
  keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
  return keys;
}
std::vector<std::uint64_t> missing(const std::vector<std::uint64_t>& sorted_add, const std::vector<std::uint64_t>& have) {
  std::vector<std::uint64_t> out;
  std::set_difference(sorted_add.begin(), sorted_add.end(), have.begin(), have.end(), std::back_inserter(out));
  return out;
}

// The evaluated corners: keys sorted, samples beside them.
struct Corners {
  std::vector<std::uint64_t> keys;
  std::vector<CornerSample> samples;
  const CornerSample& at(std::uint64_t key) const {
    return samples[std::size_t(std::lower_bound(keys.begin(), keys.end(), key) - keys.begin())];
  }
  void merge(const std::vector<std::uint64_t>& new_keys, const std::vector<CornerSample>& new_samples) {
    std::vector<std::uint64_t> k;
    std::vector<CornerSample> s;
    k.reserve(keys.size() + new_keys.size());
    s.reserve(k.capacity());
    std::size_t i = 0, j = 0;
    while (i < keys.size() || j < new_keys.size()) {
      if (j == new_keys.size() || (i < keys.size() && keys[i] < new_keys[j])) {
        k.push_back(keys[i]);
        s.push_back(samples[i++]);
      } else {
        k.push_back(new_keys[j]);
        s.push_back(new_samples[j++]);
      }
    }
    keys.swap(k);
    samples.swap(s);
  }
};

std::vector<std::uint64_t> merged(const std::vector<std::uint64_t>& a, const std::vector<std::uint64_t>& b) {
  std::vector<std::uint64_t> out;
  out.reserve(a.size() + b.size());
  std::merge(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(out));
  return out;
}

// The four corners of each face of a cube, and the neighbour across it.
constexpr int kFaces[6][4] = {{0, 2, 4, 6}, {1, 3, 5, 7}, {0, 1, 4, 5}, {2, 3, 6, 7}, {0, 1, 2, 3}, {4, 5, 6, 7}};
const ivec3 kAcross[6] = {{-1, 0, 0}, {1, 0, 0}, {0, -1, 0}, {0, 1, 0}, {0, 0, -1}, {0, 0, 1}};

// Whether the implicit changes sign between two corners both farther from the surface than
// `most` per cube side of their distance: where the surface passes between two points, a
// distance to it is at most their distance at either end. Inside a part thinner than the
// fits' support the far end's value may be larger (MLS blends both sides), never the near
// end's; where both are, the sign changes across a jump of the implicit (normals oriented
// apart), not across the surface. Unless the data put both on their sides: then the data's
// surface passes between them, whatever the distances.
bool jumps(const CornerSample (&at)[8], float most) {
  for (int a = 0; a < 8; ++a)
    for (int b = a + 1; b < 8; ++b)
      if ((at[a].distance < 0) != (at[b].distance < 0) && !(at[a].side_from_data && at[b].side_from_data) &&
          std::min(std::abs(at[a].distance), std::abs(at[b].distance)) >
              most * std::sqrt(float(std::popcount(unsigned(a ^ b)))))
        return true;
  return false;
}

}  // namespace

ivec3 Lattice::cube_of(vec3 p) const {
  const glm::dvec3 x = glm::floor((glm::dvec3(p) - origin) / cell);
  const glm::dvec3 limit(double(1 << kBits));
  return ivec3(glm::clamp(x, glm::dvec3(-1.0), limit));
}

std::int64_t band_cube_limit(std::int64_t memory) {
  if (memory <= 0) return kBandCubesWithoutMemory;
  return std::int64_t(0.75 * double(memory) / kBandBytesPerCube);
}

void check_band(double expected_cubes, double cell, const char* data) {
  const std::int64_t memory = physical_memory_bytes();
  const std::int64_t limit = band_cube_limit(memory);
  if (expected_cubes <= double(limit)) return;
  char message[400];
  const int written = std::snprintf(message, sizeof message,
                                    "the cell size %g is too small for this %s: about %.3g cubes near its surface, "
                                    "more than the %lld a mesh may take",
                                    cell, data, expected_cubes, (long long)limit);
  if (memory > 0)
    std::snprintf(message + written, sizeof message - std::size_t(written),
                  " (%.3g GB at %g bytes a cube in three quarters of this machine's %.3g GB)",
                  double(limit) * kBandBytesPerCube * 1e-9, kBandBytesPerCube, double(memory) * 1e-9);
  throw Error(std::string(message) + "; use a larger cell");
}

Lattice lattice_over(vec3 lo, vec3 hi, double margin, double cell, const char* what, double shown_scale) {
  Lattice l;
  l.cell = cell;
  l.origin = glm::dvec3(lo) - margin;
  const glm::dvec3 extent = glm::dvec3(hi) - glm::dvec3(lo) + 2 * margin;
  const glm::dvec3 corners = glm::ceil(extent / cell) + 2.0;
  const double most = double((1 << Lattice::kBits) - 1);
  if (!(corners.x <= most && corners.y <= most && corners.z <= most)) {
    char message[300];
    std::snprintf(message, sizeof message,
                  "%s %g is too small for the data's extent (%g x %g x %g): more than %.0f cells along an axis",
                  what, cell * shown_scale, extent.x * shown_scale, extent.y * shown_scale, extent.z * shown_scale,
                  most);
    throw Error(message);
  }
  l.size = ivec3(corners);
  return l;
}

namespace {

// The march of march_tetrahedra within `within` (all the lattice where null), keyed for
// welding (MarchedPiece) where `within` is given; its pinches left, its normals unturned.
MarchedPiece march(const Lattice& lattice, std::span<const vec3> seeds, const ImplicitSurface& implicit,
                   float max_slope, float crease_angle, MarchCounts& counts, std::int64_t expected_corners,
                   const CubeBox* within) {
  counts = {};
  Corners corners;
  std::vector<std::uint64_t> visited, frontier;
  std::vector<std::pair<std::uint64_t, int>> crossed;  // a cube's key, its negative corners (bit c: corner c)
  auto consider = [&](std::vector<std::uint64_t>& into, ivec3 cube) {
    if (lattice.holds_cube(cube) && (within == nullptr || within->holds(cube))) into.push_back(Lattice::key(cube));
  };
  for (const vec3& s : seeds) consider(frontier, lattice.cube_of(s));
  frontier = unique_sorted(std::move(frontier));

  // One phase for the band's corners, wave after wave, its total the estimate until the waves
  // pass it.
  std::optional<Progress> progress;
  std::int64_t planned = 0, seen = 0;
  while (!frontier.empty()) {
    visited = merged(visited, frontier);
    counts.cubes_visited += std::int64_t(frontier.size());
    // The corners of the new cubes not evaluated yet, in one batch.
    std::vector<std::uint64_t> wanted;
    wanted.reserve(frontier.size() * 8);
    for (std::uint64_t cube : frontier)
      for (int c = 0; c < 8; ++c) wanted.push_back(Lattice::key(Lattice::corner(cube) + offset(c)));
    const std::vector<std::uint64_t> fresh = missing(unique_sorted(std::move(wanted)), corners.keys);
    std::vector<vec3> positions(fresh.size());
    for (std::size_t i = 0; i < fresh.size(); ++i) positions[i] = lattice.position(Lattice::corner(fresh[i]));
    std::vector<CornerSample> samples(fresh.size());
    seen += std::int64_t(fresh.size());
    if (!progress) {
      planned = std::max(seen, expected_corners);
      progress.emplace("mesh corners", planned);
    } else if (seen > planned) {
      progress->add_total(seen - planned);
      planned = seen;
    }
    implicit.sample(positions, samples, *progress);
    counts.corners += std::int64_t(fresh.size());
    corners.merge(fresh, samples);

    std::vector<std::uint64_t> next;
    for (const CornerSample& s : samples)
      if (s.valid && s.on_surface) consider(next, lattice.cube_of(s.surface_point));
    for (std::uint64_t key : frontier) {
      const ivec3 cube = Lattice::corner(key);
      CornerSample at[8];
      bool valid = true;
      int negative = 0;
      for (int c = 0; c < 8; ++c) {
        at[c] = corners.at(Lattice::key(cube + offset(c)));
        valid = valid && at[c].valid;
        negative |= (at[c].distance < 0) << c;
      }
      if (negative == 0 || negative == 255) continue;
      if (!valid || jumps(at, max_slope * float(lattice.cell))) {
        ++counts.cubes_refused;
        continue;
      }
      crossed.push_back({key, negative});
      for (int f = 0; f < 6; ++f) {
        const int signs = (negative >> kFaces[f][0] & 1) + (negative >> kFaces[f][1] & 1) +
                          (negative >> kFaces[f][2] & 1) + (negative >> kFaces[f][3] & 1);
        if (signs != 0 && signs != 4) consider(next, cube + kAcross[f]);
      }
    }
    frontier = missing(unique_sorted(std::move(next)), visited);
  }
  progress.reset();
  release(visited);
  std::sort(crossed.begin(), crossed.end());
  counts.cubes_crossed = std::int64_t(crossed.size());

  // The triangles, each vertex an edge's key until the edges are solved.
  std::vector<std::array<std::uint64_t, 3>> triangles;
  mesh_detail::CubeTriangles cubes;
  cubes.lowest.reserve(crossed.size());
  cubes.first.reserve(crossed.size() + 1);
  for (const auto& [key, negative] : crossed) {
    const ivec3 cube = Lattice::corner(key);
    cubes.lowest.push_back(lattice.position(cube));
    cubes.first.push_back(triangles.size());
    for (int t = 0; t < 6; ++t) {
      int mask = 0;
      for (int i = 0; i < 4; ++i) mask |= (negative >> kTetrahedra[t][i] & 1) << i;
      const Case& c = kCases.at[t][mask];
      for (int k = 0; k < c.triangles; ++k)
        triangles.push_back({edge_key(cube, c.triangle[k][0]), edge_key(cube, c.triangle[k][1]),
                             edge_key(cube, c.triangle[k][2])});
    }
  }
  cubes.first.push_back(triangles.size());
  MarchedPiece piece;
  std::vector<std::uint64_t> cube_keys;
  if (within != nullptr)
    for (const auto& [key, negative] : crossed) cube_keys.push_back(key);
  release(crossed);
  std::vector<std::uint64_t> edges;
  edges.reserve(triangles.size() * 3);
  for (const auto& t : triangles) edges.insert(edges.end(), t.begin(), t.end());
  edges = unique_sorted(std::move(edges));
  edges.shrink_to_fit();  // 3 keys a triangle before, about 1.5 after
  if (edges.size() > std::size_t(INT32_MAX) || triangles.size() > std::size_t(INT32_MAX))
    throw Error("the mesh would have more than 2^31 vertices or triangles: use a larger cell");
  std::vector<EdgeCrossing> crossings(edges.size());
  cpu::parallel_for(std::int64_t(edges.size()), [&](std::int64_t i) {
    const ivec3 lower = Lattice::corner(edges[std::size_t(i)] >> 3);
    const ivec3 upper = lower + offset(int(edges[std::size_t(i)] & 7));
    crossings[std::size_t(i)] = {lattice.position(lower), lattice.position(upper),
                                 corners.at(Lattice::key(lower)).distance, corners.at(Lattice::key(upper)).distance};
  });
  // Each step frees what the next does not read: at 10^6 points the band's arrays held half
  // a gigabyte through the creases and the pinches (issue 28).
  release(corners.keys);
  release(corners.samples);
  std::vector<MeshVertex> vertices(edges.size());
  implicit.cross(crossings, vertices);
  release(crossings);

  TriangleMesh& mesh = piece.mesh;
  mesh.positions.resize(vertices.size());
  mesh.normals.resize(vertices.size());
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    mesh.positions[i] = vertices[i].position;
    mesh.normals[i] = vertices[i].normal;
  }
  release(vertices);
  mesh.triangles.resize(triangles.size());
  cpu::parallel_for(std::int64_t(triangles.size()), [&](std::int64_t i) {
    for (std::size_t k = 0; k < 3; ++k)
      mesh.triangles[std::size_t(i)][k] =
          int(std::lower_bound(edges.begin(), edges.end(), triangles[std::size_t(i)][k]) - edges.begin());
  });
  release(triangles);
  if (within != nullptr)
    piece.vertex_key = std::move(edges);
  else
    release(edges);
  const mesh_detail::CreaseCounts creases =
      mesh_detail::snap_creases(mesh, cubes, float(lattice.cell), implicit, crease_angle);
  counts.crease_vertices = creases.vertices;
  counts.crease_flips = creases.flips;
  if (within != nullptr) {
    for (const std::size_t c : cubes.centres) piece.vertex_key.push_back(cube_keys[c] << 3);
    piece.triangle_cube.resize(mesh.triangles.size());
    piece.triangle_place.resize(mesh.triangles.size());
    for (std::size_t c = 0; c + 1 < cubes.first.size(); ++c)
      for (std::size_t t = cubes.first[c]; t < cubes.first[c + 1]; ++t) {
        piece.triangle_cube[t] = cube_keys[c];
        piece.triangle_place[t] = std::int32_t(t - cubes.first[c]);
      }
  }
  return piece;
}

}  // namespace

TriangleMesh march_tetrahedra(const Lattice& lattice, std::span<const vec3> seeds, const ImplicitSurface& implicit,
                              float max_slope, float crease_angle, MarchCounts& counts, std::int64_t expected_corners) {
  TriangleMesh mesh =
      march(lattice, seeds, implicit, max_slope, crease_angle, counts, expected_corners, nullptr).mesh;
  counts.pinched_triangles = remove_pinches(mesh);
  counts.normals_turned = normals_follow_winding(mesh);
  return mesh;
}

MarchedPiece march_piece(const Lattice& lattice, std::span<const vec3> seeds, const ImplicitSurface& implicit,
                         float max_slope, float crease_angle, const CubeBox& marched, const CubeBox& kept,
                         MarchCounts& counts) {
  MarchedPiece all = march(lattice, seeds, implicit, max_slope, crease_angle, counts, 0, &marched);
  // The kept cubes' triangles, in their cubes' order, and the vertices they use.
  MarchedPiece piece;
  std::vector<int> renumber(all.mesh.positions.size(), -1);
  counts.cubes_crossed = 0;
  for (std::size_t t = 0; t < all.mesh.triangles.size(); ++t) {
    const std::uint64_t cube = all.triangle_cube[t];
    if (!kept.holds(Lattice::corner(cube))) continue;
    counts.cubes_crossed += all.triangle_place[t] == 0;
    std::array<int, 3> triangle = all.mesh.triangles[t];
    for (int& v : triangle) {
      int& to = renumber[std::size_t(v)];
      if (to < 0) {
        to = int(piece.mesh.positions.size());
        piece.mesh.positions.push_back(all.mesh.positions[std::size_t(v)]);
        piece.mesh.normals.push_back(all.mesh.normals[std::size_t(v)]);
        piece.vertex_key.push_back(all.vertex_key[std::size_t(v)]);
      }
      v = to;
    }
    piece.mesh.triangles.push_back(triangle);
    piece.triangle_cube.push_back(cube);
    piece.triangle_place.push_back(all.triangle_place[t]);
  }
  return piece;
}

std::int64_t remove_pinches(TriangleMesh& mesh, std::vector<float>* follow) {
  std::int64_t removed = 0;
  for (;;) {
    mesh_detail::Incidence in = mesh_detail::incidence(mesh.triangles);
    const std::size_t nt = mesh.triangles.size();
    // Each vertex's fans with their sizes; the largest (the least label on a tie) stays.
    std::vector<std::int64_t> size(3 * nt, 0);
    for (std::size_t c = 0; c < 3 * nt; ++c) ++size[std::size_t(in.fans.find(std::int64_t(c)))];
    std::vector<std::int64_t> keep(mesh.positions.size(), -1);
    for (std::size_t c = 0; c < 3 * nt; ++c) {
      const auto v = std::size_t(mesh.triangles[c / 3][c % 3]);
      const std::int64_t fan = in.fans.find(std::int64_t(c));
      const std::int64_t kept = keep[v];
      if (kept < 0 || size[std::size_t(fan)] > size[std::size_t(kept)] ||
          (size[std::size_t(fan)] == size[std::size_t(kept)] && fan < kept))
        keep[v] = fan;
    }
    std::vector<std::array<int, 3>> kept_triangles;
    kept_triangles.reserve(nt);
    for (std::size_t t = 0; t < nt; ++t) {
      bool pinched = false;
      for (std::size_t k = 0; k < 3; ++k)
        pinched = pinched || in.fans.find(std::int64_t(3 * t + k)) != keep[std::size_t(mesh.triangles[t][k])];
      if (!pinched) kept_triangles.push_back(mesh.triangles[t]);
    }
    if (kept_triangles.size() == nt) break;
    removed += std::int64_t(nt - kept_triangles.size());
    mesh.triangles.swap(kept_triangles);
  }
  drop_unused_vertices(mesh, follow);
  return removed;
}

}  // namespace pss
