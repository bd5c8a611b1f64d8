#include "pss/mesh/mesh_cloud.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <span>
#include <string>

#include "implicit_surface.hpp"
#include "incidence.hpp"
#include "vertex_cells.hpp"
#include "pss/core/error.hpp"
#include "pss/backend/cpu/parallel_for.hpp"
#include "pss/core/text.hpp"
#include "pss/mesh/coarsen.hpp"
#include "pss/mesh/cloud_implicit.hpp"
#include "pss/points/project_cloud.hpp"
#include "pss/points/unit_frame.hpp"
#include "pss/spatial/grid_mirror.hpp"

namespace pss {

namespace {

// The share of a mesh's area its closed parts must have for their volume to turn it.
constexpr double kClosedShareToTurn = 0.5;

// Points on a line (or all but coincident) define no surface: MLS would fit a tube of its
// weights' width around them. Refused where every point lies within 10⁻⁶ of the cloud's
// extent of the line through its mean along its principal axis (check_neighbourhood refuses
// points that all coincide).
void check_not_a_line(std::span<const vec3> points) {
  glm::dvec3 mean(0.0);
  for (const vec3& p : points) mean += glm::dvec3(p) / double(points.size());
  double c[3][3] = {};
  for (const vec3& p : points) {
    const glm::dvec3 d = glm::dvec3(p) - mean;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) c[i][j] += d[i] * d[j];
  }
  // Power iteration for the principal axis, from the covariance's column of its largest
  // variance: never orthogonal to its range, which a fixed start can be (a plane whose normal
  // it is), and never zero where the points do not all coincide.
  int longest = 0;
  for (int j = 1; j < 3; ++j)
    if (c[j][j] > c[longest][longest]) longest = j;
  glm::dvec3 axis(c[0][longest], c[1][longest], c[2][longest]);
  for (int k = 0; k < 100; ++k) {
    glm::dvec3 next(0.0);
    for (int i = 0; i < 3; ++i) next[i] = c[i][0] * axis[0] + c[i][1] * axis[1] + c[i][2] * axis[2];
    axis = next / glm::length(next);
  }
  double along = 0, off = 0;
  for (const vec3& p : points) {
    const glm::dvec3 d = glm::dvec3(p) - mean;
    along = std::max(along, std::abs(glm::dot(d, axis)));
    off = std::max(off, glm::length(d - glm::dot(d, axis) * axis));
  }
  if (off <= 1e-6 * along) throw Error("the points lie on a line: they define no surface to mesh");
}

}  // namespace

void finish_cloud_mesh(CloudMesh& out, const ProjectionParams& projection) {
  // Which side is out is a guess where the normals were estimated, and where the file's
  // disagreed among themselves (some turned: the side kept is a vote's). A file that faces
  // one way throughout, none turned, keeps its side (a room's scan faces into the room). The closed
  // parts' volume tells it where they are most of the mesh; where most is open (an aerial
  // scan's ground and roofs), a few closed blobs would decide by chance, and the guess (the
  // highest sample facing up) stands.
  // Then each closed part faces out by its depth (face_closed_parts_outward), from the same
  // components and volumes.
  const bool guessed = out.normals == NormalsUsed::estimated || out.normals_turned > 0;
  if (guessed && !out.mesh.triangles.empty()) {
    mesh_detail::Incidence in = mesh_detail::incidence(out.mesh.triangles);
    mesh_detail::ComponentVolumes parts = mesh_detail::component_volumes(out.mesh, in);
    double closed_share = 0;
    if (mesh_detail::enclosed_volume(parts, &closed_share) < 0 && closed_share >= kClosedShareToTurn) {
      turn_inside_out(out.mesh);
      for (double& volume : parts.volume) volume = -volume;
      out.turned_outward = true;
    }
    out.counts.closed_parts_turned = mesh_detail::face_closed_parts_outward(out.mesh, in, parts);
  }
  if (out.mesh.triangles.empty())
    throw Error("the surface gave no triangle with h = " + format_number(projection.h) + ", rho = " +
                format_number(projection.rho) +
                ": either is likely too small for the sample spacing (pss info suggests h; rho is 2h by default), or "
                "the cell too large");
}

double expected_band_cubes(std::span<const float> widths, double cell) {
  double cubes = 0;
  for (const float h : widths) cubes += double(h) * double(h) / (cell * cell);
  return cubes / 3;
}

Lattice cloud_lattice(const Aabb& box, const UnitFrame& frame, BorderMode borders, double widest_rho, double cell,
                      bool cell_given) {
  const double reach = borders == BorderMode::extend ? widest_rho + cell : 0.0;
  return lattice_over(frame.to_unit(box.lo), frame.to_unit(box.hi), std::max(2.0 * cell, reach) + 0.5 * cell, cell,
                      cell_given ? "the cell size" : "the cell size (h/2, from h)", frame.scale);
}

float mesh_cell(const MeshParams& params) {
  const ProjectionParams& projection = params.projection;
  validate(projection);
  if (!(params.crease_angle > 0 && params.crease_angle <= 180))
    throw Error("the crease angle must lie in (0, 180] degrees (got " + std::to_string(params.crease_angle) + ")");
  if (!(params.cell >= 0) || !std::isfinite(params.cell))
    throw Error("the cell size must be a positive number (got " + std::to_string(params.cell) + ")");
  const float cell = params.cell > 0 ? params.cell : kDefaultCellPerH * projection.h;
  // A cube the surface crosses has corners up to its diagonal, √3 cells, off the surface, and
  // a corner's projection needs samples within its support (at least ρ): a 6,000-point
  // sphere stays closed up to a cell of ρ/2 and opens at 0.55ρ, and the bunny broke into a
  // hundred pieces at 0.9ρ.
  if (cell > 0.5f * projection.rho)
    throw Error("the cell size " + format_number(cell) + " is larger than rho/2 = " +
                format_number(0.5f * projection.rho) + " (h = " + format_number(projection.h) + ", rho = " +
                format_number(projection.rho) +
                "): a cube's corners would lie beyond the samples' supports and the mesh would break apart; for a "
                "coarser mesh give a larger h as well");
  return cell;
}

CloudMesh mesh_cloud(const PointCloud& cloud, const MeshParams& params, Backend backend, Stats& stats) {
  const ProjectionParams& projection = params.projection;
  CloudMesh out;
  out.cell = mesh_cell(params);
  if (cloud.size() < 3)
    throw Error("a mesh needs at least 3 points (the cloud has " + std::to_string(cloud.size()) + ")");
  // The mesh is made in the cloud's unit frame (points/unit_frame.hpp), as project_cloud's
  // projections are and as tile by tile (tiles/mesh.hpp), from the same floats: so the tiles'
  // mesh is this one to the last bit. Its vertices are mapped back at the end.
  const UnitFrame frame = unit_frame(cloud.positions);
  check_neighbourhood(projection, frame.diagonal, cloud.size());
  check_not_a_line(cloud.positions);
  const ProjectionParams unit_params = in_unit_frame(projection, frame.scale);
  const double cell = double(out.cell) / frame.scale;
  const float asked = params.cell > 0 ? float(double(params.cell) / frame.scale) : 0.0f;
  {
    ScopedPhase phase(stats, "support widths", projection.support == Support::global);
    out.widths = support_widths(cloud.positions, projection);  // from the points as read, as in tiles
  }
  for (float& w : out.widths.h) w = float(double(w) / frame.scale);
  const std::vector<vec3> unit = to_unit(cloud.positions, frame);
  const float kappa = unit_params.rho / unit_params.h;
  const double widest_rho = double(kappa) * double(*std::max_element(out.widths.h.begin(), out.widths.h.end()));
  const Lattice lattice = cloud_lattice(cloud.bounds(), frame, projection.borders, widest_rho, cell, params.cell > 0);
  const double band_cubes = expected_band_cubes(out.widths.h, cell);
  check_band(band_cubes, double(out.cell), "cloud");
  SupportGrid grid = grid_of_samples(unit, out.widths.h, out.widths.merged, kappa, projection.outliers, backend,
                                     stats, out.outliers);
  out.widths.h = {};
  out.widths.merged = {};
  // Every operator's mesh needs the samples' oriented normals: they say which side is out.
  const FileNormals file = file_normals(grid, cloud.normals, unit_params, stats);
  out.normals_turned = file.turned;
  out.file_normals_off = file.off_the_points;
  grid.set_normals(sample_normals(grid, file, unit_params, backend, stats, out.normals));

  const GridMirror g(backend, grid);
  const ImplicitSurface implicit =
      mesh_detail::implicit_surface(backend, CloudImplicit{g.view(), unit_params}, float(cell), stats);
  {
    ScopedPhase phase(stats, "mesh", false);  // its kernels show their progress
    out.mesh = march_tetrahedra(lattice, grid.sorted_points(), implicit, mesh_detail::kMaxSlope,
                                params.crease_angle, out.counts, std::int64_t(kCornersPerBandCube * band_cubes));
  }
  {
    ScopedPhase phase(stats, "coarsen", true);
    coarsen_mesh(out.mesh, mesh_detail::vertex_cells(out.mesh.positions, grid, asked, float(cell)), out.counts);
  }
  out.counts.unsupported_parts = remove_unsupported_parts(
      out.mesh, [&](std::span<const vec3> centre, std::span<const float> radius, std::span<int> inside) {
        cpu::parallel_for(std::int64_t(centre.size()), [&](std::int64_t p) {
          const vec3 c = centre[std::size_t(p)];
          const float r = radius[std::size_t(p)];
          for (const SupportLevel& level : grid.levels_on_host())
            level.grid.for_each_near(c, r, [&](vec3 s, int) { inside[std::size_t(p)] += glm::length(s - c) <= r; });
        });
      });
  for (vec3& p : out.mesh.positions) p = frame.from_unit(p);
  out.mesh.origin = cloud.origin;
  finish_cloud_mesh(out, projection);
  return out;
}

}  // namespace pss
