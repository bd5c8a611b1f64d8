// pss info FILE: what a cloud is and the h that pss would use for it; or what a volume is
// (dimensions, voxel type, geometry, values and their histogram) and the iso-values its
// histogram suggests.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "commands.hpp"
#include "numbers.hpp"
#include "pss/core/error.hpp"
#include "pss/core/text.hpp"
#include "pss/io/point_cloud_file.hpp"
#include "pss/io/point_stream.hpp"
#include "pss/io/tiled_cloud.hpp"
#include "pss/io/volume_file.hpp"
#include "pss/points/outliers.hpp"
#include "pss/points/sample_normals.hpp"
#include "pss/points/spacing.hpp"
#include "pss/points/support.hpp"
#include "pss/tiles/memory_plan.hpp"
#include "pss/tiles/spacing.hpp"
#include "pss/tiles/support.hpp"
#include "pss/volume/histogram.hpp"
#include "raw_volume_options.hpp"

namespace pss::app {

namespace {

// A bound in world coordinates with the fewest digits that read back as the same float
// about the cloud's origin (cloud.hpp): the file's own digits (-0.0946899, not
// -0.09468989819), and a georeferenced cloud's all of them, which %g's six would cut.
std::string world_coordinate(double origin, float local) {
  char text[32];
  // At least the integer digits, so that -99.99999 reads -100, not -1e+02.
  const double magnitude = std::abs(origin + double(local));
  for (int digits = magnitude >= 1 ? std::min(17, int(std::floor(std::log10(magnitude))) + 1) : 1;; ++digits) {
    std::snprintf(text, sizeof text, "%.*g", digits, origin + double(local));
    if (digits == 17 || float(std::strtod(text, nullptr) - origin) == local) return text;
  }
}

// 1st, 2nd, 3rd, 4th, ..., 11th, 12th, 13th, ..., 21st.
std::string ordinal(int k) {
  const char* suffix = (k % 100 >= 11 && k % 100 <= 13) ? "th"
                       : k % 10 == 1                    ? "st"
                       : k % 10 == 2                    ? "nd"
                       : k % 10 == 3                    ? "rd"
                                                        : "th";
  return std::to_string(k) + suffix;
}

// Whether the file's normals follow the points and face one way, as render would find with
// its defaults (its grid of the samples, merged and outliers set aside, on the points as read).
void print_file_normals(const PointCloud& cloud, const SupportWidths& widths, const ProjectionParams& params) {
  Stats stats;
  OutlierReport outliers;
  const SupportGrid grid = grid_of_samples(cloud.positions, widths.h, widths.merged, params.rho / params.h,
                                           params.outliers, Backend::cpu, stats, outliers);
  const FileNormals file = file_normals(grid, cloud.normals, params, stats);
  if (file.off_the_points > 0)
    std::printf("normals         the file's: those of %zu of %zu samples lie more than 45 degrees off their neighbours' "
                "plane: they do not follow the points (render and project estimate them)\n",
                file.off_the_points, grid.sorted_points().size());
  else if (file.sorted.empty())
    std::printf("normals         the file's: one or more has no direction (render and project estimate them)\n");
  else if (file.turned == 0)
    std::printf("normals         the file's follow the points and face one way\n");
  else
    std::printf("normals         the file's: render and project turn %zu of %zu (a part faced inward, or was flipped "
                "against the rest)\n", file.turned, cloud.size());
}

// What pss info says of a cloud, found in core or tile by tile.
struct CloudSummary {
  std::uint64_t points = 0;
  bool normals = false, colors = false;
  glm::dvec3 origin{0.0};
  Aabb box;
  SpacingEstimate spacing{};
  SupportWidths widths;  // least, median, largest
  std::string widths_refused;  // why they are not given
};

// Bytes a point (tiles/memory_plan.hpp): in core, measured at 88 on a 10^6-point torus; beside
// the tiles, each point's spacing, its least neighbour's and its width; a tile's point, its record, unit position,
// margin, the widths' steps and the trees over it.
constexpr MemoryCosts kInfoCosts{96, 12, 128};

ProjectionParams adaptive_params(const SpacingEstimate& s) {
  ProjectionParams params = ProjectionParams::from_h(float(s.suggested_h));
  params.support = Support::adaptive;
  return params;
}

void print_summary(const std::string& path, const CloudSummary& c) {
  const vec3 size = c.box.extent();
  std::printf("file            %s\n", path.c_str());
  const char* extras = c.normals ? (c.colors ? " (with normals and colours)" : " (with normals)")
                                 : (c.colors ? " (with colours)" : "");
  std::printf("points          %llu%s\n", (unsigned long long)c.points, extras);
  std::printf("bounds          ");
  for (int k = 0; k < 3; ++k)
    std::printf("%s[%s, %s]", k ? " x " : "", world_coordinate(c.origin[k], c.box.lo[k]).c_str(),
                world_coordinate(c.origin[k], c.box.hi[k]).c_str());
  std::printf("\n");
  const double diagonal = glm::length(glm::dvec3(size));  // in double: a box of 10²⁰ overflows a float's square
  std::printf("size            %g x %g x %g (diagonal %g)\n", size.x, size.y, size.z, diagonal);
  if (c.points < 2) return;
  const SpacingEstimate& s = c.spacing;
  std::printf("spacing         %g mean nearest-neighbour distance\n", s.mean_nearest);
  if (s.suggested_h > s.median_kth)
    std::printf("suggested h     %g (%g times the noise, over the median distance to the %s nearest neighbour, %g; "
                "rho = 2h = %g)\n",
                s.suggested_h, kNoiseWidths, ordinal(s.k).c_str(), s.median_kth, 2 * s.suggested_h);
  else
    std::printf("suggested h     %g (median distance to the %s nearest neighbour; rho = 2h = %g)\n", s.suggested_h,
                ordinal(s.k).c_str(), 2 * s.suggested_h);
  // project, render and mesh refuse a neighbourhood wider than the cloud (check_neighbourhood).
  if (2 * s.suggested_h > diagonal)
    std::printf("too few points  rho = 2h spans the whole cloud (diagonal %g): project, render and mesh refuse it "
                "without a smaller --h\n", diagonal);
  // The scatter about the surface (points/noise.hpp): h stays over kNoiseWidths times it.
  std::printf("noise           %g (sigma of the samples about a quadric fitted to their neighbours; median)\n",
              s.noise);
  // Where the spacing varies, one h cannot serve the whole cloud: the spread says by how much.
  std::printf("%-15s min %g, median %g, max %g (max/min %.3g)\n", (ordinal(s.k) + " neighbour").c_str(), s.min_kth,
              s.median_kth, s.max_kth, s.max_kth / s.min_kth);
  // What render, project and view use without --h (points/support.hpp).
  if (!c.widths_refused.empty())
    std::printf("adaptive h_i    not given: %s\n", c.widths_refused.c_str());
  else
    std::printf("adaptive h_i    from %g to %g, median %g (wider where the spacing is, across the gaps of a cloud "
                "sampled in rows, or where the noise is; --support global uses h everywhere)\n",
                double(c.widths.least), double(c.widths.largest), double(c.widths.median));
  if (c.widths_refused.empty() && c.widths.merged_count > 0)  // points/merged_samples.hpp
    std::printf("merged samples  %lld points, where the noise widens a support past %g samples: each cube about "
                "h_i/2 to h_i wide is one sample that weighs as many as it holds\n",
                (long long)c.widths.merged_count, kSupportSamplesMost);
}

void print_cloud_in_core(const std::string& path, const MemoryPlan& plan) {
  const PointCloud cloud = read_point_cloud(path);
  CloudSummary c;
  c.points = cloud.size();
  c.normals = cloud.has_normals();
  c.colors = cloud.has_colors();
  c.origin = cloud.origin;
  c.box = cloud.bounds();
  ProjectionParams params;
  if (cloud.size() >= 2) {
    c.spacing = estimate_spacing_of(cloud, path);
    params = adaptive_params(c.spacing);
    c.widths = support_widths(cloud.positions, params);
  }
  print_summary(path, c);
  if (cloud.size() >= 2 && cloud.has_normals()) print_file_normals(cloud, c.widths, params);
  std::printf("memory          in core (pss info needs about %s; --memory %s)\n",
              byte_size(double(cloud.size() * kInfoCosts.in_core)).c_str(), byte_size(double(plan.budget)).c_str());
}

// A cloud larger than the budget, tile by tile (issue 28): the same figures as in core.
void print_cloud_in_tiles(const std::string& path, const MemoryPlan& plan) {
  const TiledCloud tiles(path, scratch_folder(), plan.points_per_tile, plan.buffer_bytes);
  CloudSummary c;
  c.points = tiles.size();
  c.normals = tiles.has_normals();
  c.colors = tiles.has_colors();
  c.origin = tiles.origin();
  c.box = tiles.size() > 0 ? tiles.bounds() : Aabb{};
  if (tiles.size() >= 2) {
    c.spacing = estimate_spacing(tiles);
    try {
      c.widths = support_widths(tiles, adaptive_params(c.spacing));
    } catch (const NotTiled& e) {
      c.widths_refused = e.what();
    }
  }
  print_summary(path, c);
  if (tiles.size() >= 2 && tiles.has_normals())
    std::printf("normals         the file's (whether they agree with their neighbours' is checked in core only)\n");
  std::printf("memory          tile by tile: %s (--memory %s)\n", tiles_text(tiles).c_str(),
              byte_size(double(plan.budget)).c_str());
}

void print_cloud(const std::string& path, std::uint64_t budget) {
  // Formats read whole (OBJ, STL, OFF, PCD) have no stream to tile: in core.
  MemoryPlan plan;
  plan.budget = budget;
  if (has_point_stream(path)) plan = plan_memory(path, budget, kInfoCosts);
  if (plan.tiled)
    print_cloud_in_tiles(path, plan);
  else
    print_cloud_in_core(path, plan);
}

constexpr int kPrintedBins = 20;
constexpr int kBarWidth = 40;

void print_volume(const std::string& path, const std::optional<RawVolumeFormat>& raw) {
  const VolumeFile file = read_volume_file(path, raw);
  const Volume& v = file.volume;
  const VolumeSource& src = file.source;
  std::printf("file            %s\n", path.c_str());
  std::printf("format          %s%s\n", src.format.c_str(), src.compressed ? " (compressed)" : "");
  std::printf("dimensions      %d x %d x %d (%lld voxels)\n", v.dims.x, v.dims.y, v.dims.z,
              static_cast<long long>(v.voxel_count()));
  std::printf("voxel type      %s%s%s%s\n", voxel_type_name(src.type),
              voxel_type_size(src.type) > 1 ? (src.big_endian ? ", big-endian" : ", little-endian") : "",
              src.note.empty() ? "" : "; ", src.note.c_str());
  std::printf("spacing         %g x %g x %g\n", v.spacing.x, v.spacing.y, v.spacing.z);
  std::printf("origin          %g, %g, %g\n", v.origin.x, v.origin.y, v.origin.z);
  const ValueStats stats = value_stats(v.values);
  std::printf("values          [%g, %g], mean %g\n", stats.min, stats.max, stats.mean);

  // A coarse view for the eye (log scale: the background would flatten everything else);
  // the suggestions come from a fine histogram (see suggest_iso_values).
  const Histogram fine = fine_histogram(v.values, stats);
  const Histogram coarse = make_histogram(v.values, stats.max > stats.min ? kPrintedBins : 1, stats.min, stats.max);
  const std::int64_t top = *std::max_element(coarse.counts.begin(), coarse.counts.end());
  std::printf("histogram       %d bins, bars on a log scale\n", coarse.bins());
  for (int b = 0; b < coarse.bins(); ++b) {
    const std::int64_t c = coarse.counts[std::size_t(b)];
    const int bar = c == 0 ? 0 : std::max(1, int(std::lround(kBarWidth * std::log1p(double(c)) / std::log1p(double(top)))));
    std::printf("  %11.5g .. %-11.5g %-*s %lld\n", coarse.edge(b), coarse.edge(b + 1), kBarWidth,
                std::string(std::size_t(bar), '#').c_str(), static_cast<long long>(c));
  }
  const std::vector<IsoSuggestion> iso = suggest_iso_values(fine);
  if (iso.empty()) {
    std::printf("suggested iso   none: the histogram has one main peak (no valley between materials); try --gradient\n");
    return;
  }
  if (iso.size() == 1 && iso[0].tail) {
    const bool up = iso[0].upper_share < iso[0].lower_share;
    std::printf("suggested iso   %-8g (where the one main peak, at %g, ends; %.1f%% of voxels lie %s)\n", iso[0].iso,
                up ? iso[0].lower_peak : iso[0].upper_peak, 100 * (up ? iso[0].upper_share : iso[0].lower_share),
                up ? "above" : "below");
    return;
  }
  for (std::size_t i = 0; i < iso.size(); ++i)
    std::printf("%s%-8g (valley between the peaks at %g, %.1f%% of voxels, and %g, %.1f%%)\n",
                i == 0 ? "suggested iso   " : "                ", iso[i].iso, iso[i].lower_peak,
                100 * iso[i].lower_share, iso[i].upper_peak, 100 * iso[i].upper_share);
}

}  // namespace

void add_info_command(CLI::App& app, Action action) {
  auto* command = app.add_subcommand(
      "info", "Print a point cloud's size, bounds, sample spacing and suggested h; or a volume's dimensions, voxel "
              "type, geometry, value histogram and suggested iso-values");
  auto path = std::make_shared<std::string>();
  auto raw = std::make_shared<RawVolumeOptions>();
  command->add_option("file", *path,
                      kCloudFormatsHelp + " or volume (.nrrd/.nhdr, .mhd/.mha, .nii/.nii.gz, or raw with --dims)")
      ->required();
  add_raw_volume_options(*command, *raw);
  auto memory = std::make_shared<std::string>();
  add_memory_option(*command, *memory, "the same figures");
  add_progress_option(*command);
  command->callback([path, raw, memory, action] {
    const std::optional<RawVolumeFormat> format = raw_volume_format(*raw, *path);
    const std::uint64_t budget = memory_budget(*memory);
    if (action == Action::check) return;
    if (format || has_volume_header(*path))
      print_volume(*path, format);
    else
      print_cloud(*path, budget);
  });
}

}  // namespace pss::app
