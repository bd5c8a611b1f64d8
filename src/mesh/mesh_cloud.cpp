#include "pss/mesh/mesh_cloud.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <span>
#include <string>

#include "pss/backend/mirror.hpp"
#include "pss/backend/parallel_for.hpp"
#include "pss/core/error.hpp"
#include "pss/mesh/cloud_implicit.hpp"
#include "pss/points/project_cloud.hpp"
#include "pss/spatial/grid_mirror.hpp"


namespace pss {

namespace {

// Regula falsi stops within this share of the cube's side of the surface, or after
// kRootSteps projections (cloud_implicit.hpp: about 2 on average).
constexpr float kRootTolerance = 1e-3f;
constexpr int kRootSteps = 8;

// Where the surface passes between two corners, the nearer lies within their distance of it
// (marching_tetrahedra.hpp: farther, the change of sign is a jump of the implicit).
constexpr float kMaxSlope = 1.0f;

// The band holds about one cube per cell² of surface, and each sample stands for about
// h_i² of it (h_i is its distance to the 15th neighbour: about 2.2 spacings): Σ (h_i/cell)²
// overestimates the cubes about 3-fold (the bunny: 144,000 for 42,000). Refused above the
// cap before any work, so that a cell too fine for the cloud costs neither hours nor memory
// (at the cap some 3 GiB of corners and keys, and as much again of the triangles' keys).
void check_band(std::span<const float> widths, float cell) {
  double cubes = 0;
  for (const float h : widths) cubes += double(h) * double(h) / (double(cell) * double(cell));
  if (cubes > double(kMaxBandCubes)) {
    char message[300];
    std::snprintf(message, sizeof message,
                  "the cell size %g is too small for this cloud: about %.3g cubes near its surface, more than "
                  "the %lld a mesh may take; use a larger cell",
                  double(cell), cubes / 3, (long long)kMaxBandCubes / 3);
    throw Error(message);
  }
}

// Points on a line (or all but coincident) define no surface: MLS would fit a tube of its
// weights' width around them. Refused where every point lies within 10⁻⁶ of the cloud's
// extent of the line through its mean along its principal axis.
void check_not_a_line(std::span<const vec3> points) {
  glm::dvec3 mean(0.0);
  for (const vec3& p : points) mean += glm::dvec3(p) / double(points.size());
  double c[3][3] = {};
  for (const vec3& p : points) {
    const glm::dvec3 d = glm::dvec3(p) - mean;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) c[i][j] += d[i] * d[j];
  }
  glm::dvec3 axis(1.0, 0.7, 0.3);  // power iteration: the principal axis
  for (int k = 0; k < 100; ++k) {
    glm::dvec3 next(0.0);
    for (int i = 0; i < 3; ++i) next[i] = c[i][0] * axis[0] + c[i][1] * axis[1] + c[i][2] * axis[2];
    const double length = glm::length(next);
    if (!(length > 0)) return;  // all coincident: the spacing's estimate says so
    axis = next / length;
  }
  double along = 0, off = 0;
  for (const vec3& p : points) {
    const glm::dvec3 d = glm::dvec3(p) - mean;
    along = std::max(along, std::abs(glm::dot(d, axis)));
    off = std::max(off, glm::length(d - glm::dot(d, axis) * axis));
  }
  if (off <= 1e-6 * along) throw Error("the points lie on a line: they define no surface to mesh");
}

template <class Kernel>
void run(Backend backend, const char* phase, std::int64_t n, const Kernel& kernel, Stats& stats) {
  Progress progress(phase, n);
  parallel_for(backend, phase, n, kernel, stats, &progress);
}

}  // namespace

CloudMesh mesh_cloud(const PointCloud& cloud, const MeshParams& params, Backend backend, Stats& stats) {
  const ProjectionParams& projection = params.projection;
  validate(projection);
  if (cloud.size() < 3)
    throw Error("a mesh needs at least 3 points (the cloud has " + std::to_string(cloud.size()) + ")");
  const Aabb box = cloud.bounds();
  check_neighbourhood(projection, double(glm::length(box.extent())));
  CloudMesh out;
  if (!(params.cell >= 0) || !std::isfinite(params.cell))
    throw Error("the cell size must be a positive number (got " + std::to_string(params.cell) + ")");
  out.cell = params.cell > 0 ? params.cell : kDefaultCellPerH * projection.h;
  check_not_a_line(cloud.positions);
  {
    ScopedPhase phase(stats, "support widths", projection.support == Support::global);
    out.widths = support_widths(cloud.positions, projection);
  }
  // The lattice reaches past the samples as far as the surface may: with extended borders,
  // the largest support ρ_i past the box (the projection's reach), else two cubes.
  const double reach = projection.borders == BorderMode::extend
                           ? double(out.widths.largest) * double(projection.rho / projection.h) + double(out.cell)
                           : 0.0;
  const Lattice lattice =
      lattice_over(box.lo, box.hi, std::max(2.0 * double(out.cell), reach), double(out.cell), "the cell size");
  check_band(out.widths.h, out.cell);
  SupportGrid grid = grid_of_samples(cloud.positions, out.widths.h, projection.rho / projection.h,
                                     projection.outliers, backend, stats, out.outliers);
  out.widths.h = {};
  // Every operator's mesh needs the samples' oriented normals: they say which side is out.
  const FileNormals file = file_normals(grid, cloud.normals, projection, stats);
  out.normals_turned = file.turned;
  grid.set_normals(sample_normals(grid, file, projection, backend, stats, out.normals));

  const GridMirror g(backend, grid);
  ImplicitSurface implicit;
  implicit.sample = [&](std::span<const vec3> corners, std::span<CornerSample> samples) {
    const Mirror<vec3> in(backend, corners);
    Mirror<CornerSample> result(backend, corners.size());
    run(backend, "mesh corners", std::int64_t(corners.size()),
        SampleCornersKernel{g.view(), in.data(), result.data(), projection}, stats);
    const std::vector<CornerSample> taken = result.take();
    std::copy(taken.begin(), taken.end(), samples.begin());
  };
  implicit.cross = [&](std::span<const EdgeCrossing> edges, std::span<MeshVertex> vertices) {
    const Mirror<EdgeCrossing> in(backend, edges);
    Mirror<MeshVertex> result(backend, edges.size());
    run(backend, "mesh vertices", std::int64_t(edges.size()),
        CrossEdgesKernel{g.view(), in.data(), result.data(), projection, kRootTolerance * out.cell, kRootSteps}, stats);
    const std::vector<MeshVertex> taken = result.take();
    std::copy(taken.begin(), taken.end(), vertices.begin());
  };
  {
    ScopedPhase phase(stats, "mesh", false);  // its kernels show their progress
    out.mesh = march_tetrahedra(lattice, grid.sorted_points(), implicit, kMaxSlope, out.counts);
  }
  out.mesh.origin = cloud.origin;
  // Which side is out is a guess where the normals were estimated, and where the file's
  // disagreed among themselves (some turned: the side kept is the larger one's).
  const bool guessed = out.normals == NormalsUsed::estimated || out.normals_turned > 0;
  if (guessed && enclosed_volume(out.mesh) < 0) {
    turn_inside_out(out.mesh);
    out.turned_outward = true;
  }
  if (out.mesh.triangles.empty())
    throw Error("the surface gave no triangle: h = " + std::to_string(projection.h) +
                " is likely too small for the sample spacing (pss info suggests one), or the cell too large");
  return out;
}

}  // namespace pss
