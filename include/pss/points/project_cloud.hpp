// Projecting every point of a cloud onto its PSS (what `pss project` does): the grid, the
// projection kernel on the chosen backend, and consistently oriented normals.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "pss/backend/backend.hpp"
#include "pss/core/progress.hpp"
#include "pss/core/stats.hpp"
#include "pss/points/cloud.hpp"
#include "pss/points/outliers.hpp"
#include "pss/points/project_points.hpp"
#include "pss/points/sample_normals.hpp"
#include "pss/points/support.hpp"

namespace pss {

struct StatusCounts {
  std::int64_t converged = 0, not_converged = 0, too_few_neighbours = 0, degenerate_normal = 0;
  void add(ProjectionStatus status) {
    switch (status) {
      case ProjectionStatus::converged: ++converged; break;
      case ProjectionStatus::not_converged: ++not_converged; break;
      case ProjectionStatus::too_few_neighbours: ++too_few_neighbours; break;
      case ProjectionStatus::degenerate_normal: ++degenerate_normal; break;
    }
  }
};

struct CloudProjection {
  PointCloud cloud;  // projected points, with normals, and the input's colours and scalars
  std::vector<ProjectionStatus> status;  // one per point
  StatusCounts counts;
  SupportWidths widths;  // least, median, largest h_i (h is not kept)
  NormalsUsed normals = NormalsUsed::none;  // the samples' normals APSS and RIMLS fitted
  std::size_t normals_turned = 0;           // the file's, contradicting the points (turn_flipped_normals.hpp)
  std::size_t file_normals_off = 0;  // the file's off their neighbours' planes, where all were left out (FileNormals)
  OutlierReport outliers;  // the points that are not samples (points/outliers.hpp); projected all the same
};

// Throws Error for invalid parameters (h or ρ not positive and finite, ρ beyond the cloud's
// bounding-box diagonal). Runs in the cloud's bounding-box frame, so results do not depend
// on the data's units. The input's arrays become the result's: a caller done with the cloud
// moves it in, and no second copy of it is held.
CloudProjection project_cloud(PointCloud input, const ProjectionParams& params, Backend backend, Stats& stats);

void validate(const ProjectionParams& params);

// The parameters' lengths (h, ρ, the tolerance on t) in a unit frame of that scale
// (unit_frame.hpp), where projection runs.
ProjectionParams in_unit_frame(const ProjectionParams& params, double scale);

// Throws Error when a cloud of points had none projected (every one with too few neighbours
// or a degenerate normal): handing the input back unmoved would look like success.
void check_some_projected(const StatusCounts& counts, const ProjectionParams& params);

// Throws Error when ρ exceeds the cloud's bounding-box diagonal (every neighbourhood the
// whole cloud), or where it is 0 and the cloud's `points` are more than one (they all
// coincide; one point has no neighbours, and no surface, which its caller says).
void check_neighbourhood(const ProjectionParams& params, double diagonal, std::uint64_t points);

}  // namespace pss
