// `pss project` tile by tile (issue 28): a cloud on disk (TiledCloud) projected onto its PSS
// within a memory budget, with project_cloud's result (points/project_cloud.hpp) to the last
// bit: every tile's grid takes the whole cloud's cells (spatial/support_layout.hpp), so its
// sums run in the in-core order; only strays' normals' signs may differ. Each step runs over
// the tiles, each tile with a halo as wide as the step reads: the widths (tiles/support.hpp),
// the outliers' passes, the file's normals and their seams' turn, for APSS and RIMLS the
// samples' normals (the file's, or estimated and oriented), the projections, and for MLS
// without the file's normals the orientation of their normals; the tiles agree on the normals'
// signs where their halos overlap (tiles/orient.hpp). Every step's tiles may be spread over
// processes (tiles/farm.hpp). The results wait in scratch files and come back in the cloud's
// order, a window at a time.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <vector>

#include "pss/backend/backend.hpp"
#include "pss/core/stats.hpp"
#include "pss/io/bucket_file.hpp"
#include "pss/io/tiled_cloud.hpp"
#include "pss/points/project_cloud.hpp"
#include "pss/points/sample_normals.hpp"
#include "pss/points/unit_frame.hpp"
#include "pss/tiles/farm.hpp"
#include "pss/tiles/orient.hpp"

namespace pss {

// Consecutive points of the cloud, in its order.
struct ProjectedWindow {
  std::uint64_t first = 0;      // the first one's index in the cloud
  std::vector<vec3> positions;  // about the cloud's origin
  std::vector<vec3> normals;
  std::vector<ProjectionStatus> status;
};

class TiledProjection {
 public:
  // Projects every point of `cloud` onto its PSS (MLS, APSS or RIMLS), each step tile by tile,
  // keeping the results in scratch files in `folder` (each buffered in at most
  // `buffer_bytes`), to be read back in windows of `window_points`. Throws Error as
  // project_cloud does, and NotTiled (tiles/memory_plan.hpp) for what tiles do not do yet:
  // adaptive widths in a cloud sampled in rows (tiles/support.hpp).
  TiledProjection(const TiledCloud& cloud, const ProjectionParams& params, Backend backend,
                  const std::filesystem::path& folder, std::size_t window_points, std::size_t buffer_bytes,
                  Stats& stats, TileFarm& farm = local_farm());

  StatusCounts counts() const { return counts_; }
  SupportWidths widths() const { return widths_; }  // least, median, largest (h is not kept)
  OutlierReport outliers() const { return outliers_; }
  NormalsUsed normals_used() const { return normals_; }  // the samples' that APSS and RIMLS fit
  std::size_t normals_turned() const { return normals_turned_; }  // the file's, contradicting the points
  std::size_t file_normals_off() const { return file_normals_off_; }  // where the file's were left out so
  std::uint64_t normals_without_direction() const { return without_direction_; }  // points' in the file
  // The points each rank of the farm projected.
  const std::vector<std::uint64_t>& points_per_rank() const { return points_per_rank_; }

  // f(window) for each window of the cloud's points, first to last (f may take its arrays).
  void read_in_order(const std::function<void(ProjectedWindow&)>& f) const;

 private:
  const TiledCloud& cloud_;
  UnitFrame frame_;
  std::size_t window_points_;
  std::unique_ptr<BucketFile> ordered_;  // the oriented results, a bucket a window
  PieceTurns pieces_;                    // per piece of a tile's orientation, whether it turns
  StatusCounts counts_;
  SupportWidths widths_;
  OutlierReport outliers_;
  NormalsUsed normals_ = NormalsUsed::none;
  std::size_t normals_turned_ = 0, file_normals_off_ = 0;
  std::uint64_t without_direction_ = 0;
  std::vector<std::uint64_t> points_per_rank_;
};

}  // namespace pss
