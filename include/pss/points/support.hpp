// The width h_i of each sample's weight exp(−‖x − p_i‖²/h_i²) (issue 26): one h for all, as
// the paper, or adaptive, from the distance to the sample's k-th nearest neighbour (Pauly et
// al. 2003; MeshLab's APSS and RIMLS filters size their supports the same way), so that the
// support holds about as many samples where the cloud is sparse as where it is dense.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "pss/points/projection.hpp"

namespace pss {

// The neighbour whose distance sets h_i: the spacing estimate's (spacing.hpp), so that on an
// evenly sampled cloud h_i is about the global h that pss info suggests.
inline constexpr int kSupportNeighbour = 15;

// Adaptive widths stay within [h, h·128]: a 60:1 spread of the spacing fits with room, and a
// stray sample far from the rest cannot spread its weight over the whole cloud.
inline constexpr float kSupportSpread = 128;

// Where the spacing s_i is wider than 4/3 of the median, h_i = kSupportWidening·h·s_i/median s:
// the width grows with the spacing but by less, since a wider width rounds creases and thin
// parts more (measured on the shipped clouds at 1, 0.75 and 0.5; docs/paper-notes.md).
inline constexpr float kSupportWidening = 0.75f;

// A sample widens only where it lies on a sparse surface: its spacing s_i above 4/3 of the
// median; no much denser sample among its k nearest neighbours (each one's own distance to
// its k-th at least kSparseEvenness·s_i); its kVolumeNeighbour nearest neighbours flat (the
// smallest eigenvalue of their covariance at most kVolumeVariation of the sum: Pauly et al.'s
// surface variation, 0 on a plane, about 0.25 for points strewn in space; 16 neighbours, about
// those its spacing is measured over: 32 wrap round a sparse thin part, a bunny's ear at 1/8
// of the density, and read it as a volume); and
// kSparseNeighbours of its k nearest neighbours alike. Outliers strewn around a surface are
// sparse and each other's neighbours: widened, they made sheets (1 % of points strewn around
// the bunny: 41–88 % of its pixels extra; with these rules 0.3–0.4 %, as with one h;
// docs/paper-notes.md).
inline constexpr float kSparseEvenness = 0.25f;
inline constexpr int kVolumeNeighbour = 16;
inline constexpr float kVolumeVariation = 0.1f;
inline constexpr int kSparseNeighbours = 4;

// Where the samples about p_i scatter by σ_i about their surface, h_i is at least
// kNoiseWidths·σ_i: the rule of the global h (spacing.hpp, h over the noise) kept where the
// noise is, so that a cloud noisy in part is smoothed there and not elsewhere. σ_i is the
// largest σ of the kRegionQueries noise queries nearest p_i, as the regions below leave it
// (one query's low estimate left bubbles: the σ of the nearest query alone gave a torus noisy
// on a quarter 135 boundary edges). A query's σ counts where
// kRegionShare of the queries within the support it asks for (2·kNoiseWidths·σ), and at least
// its kRegionQueries nearest, measured at least half of it: a noisy region is as wide as that
// support, while a tree crown in a LiDAR tile (its returns scatter as noise) or strays strewn
// around a surface are not; each region's σ then spreads over the queries within the support
// it asks for, so that its edge, short of the share, widens too. Without the share, 6.6 % of
// urban.las widened, up to 6 h, and its trees merged into sheets (docs/paper-notes.md).
inline constexpr std::size_t kRegionQueries = 5;
inline constexpr double kRegionShare = 0.67;

// What the command line and the Python module choose when the support is not named: adaptive,
// unless an h was given, which fixes one width for every sample (the paper).
inline Support default_support(bool h_given) { return h_given ? Support::global : Support::adaptive; }
inline const char* support_name(Support s) { return s == Support::global ? "global" : "adaptive"; }

// The most samples a support needs: where one would hold more (the widths noise widens,
// h_i = kNoiseWidths·σ_i, take in thousands where σ is a few spacings), its samples are merged
// (points/merged_samples.hpp). Evenly sampled clouds at the spacing's h hold about 60 (ρ = 2h,
// h = s): never merged. A 200,000-point torus with noise 0.02 R holds some 600: merged, its
// projections 9× faster and its frames 18×, as close to the true torus (docs/paper-notes.md).
inline constexpr double kSupportSamplesMost = 400;

// Whether a sample's support would hold over kSupportSamplesMost samples where it lies in
// noise (σ_i > 0; clean clouds keep every sample, however their sampling runs), from its
// width h_i, its spacing s_i (the distance to its k-th neighbour) and σ_i in the same units,
// and kappa = ρ_i/h_i.
bool merges_samples(float h, float spacing, float sigma, float kappa);

// The noise the cloud's h stands for: h/kNoiseWidths where h is over twice the median spacing
// (the default h is the larger of the spacing's and kNoiseWidths·σ̂, spacing.hpp), else 0. The
// noise queries near a sample miss noise above about 1.5 spacings (docs/paper-notes.md)
// that the cloud's σ̂ saw.
float noise_of_h(float h, float median_spacing);

struct SupportWidths {
  std::vector<float> h;  // one per point, in the input's order
  float least = 0, median = 0, largest = 0;
  // Per point, whether merges_samples holds, and its samples are merged; empty where none is.
  std::vector<char> merged;
  std::int64_t merged_count = 0;
};

// params.h for every point (Support::global), or (Support::adaptive) h_i = params.h ·
// max(1, kSupportWidening·s_i / median s) where p_i lies on a sparse surface (above), else
// params.h, and at least kNoiseWidths·σ_i (above); s_i the median over p_i and its k nearest
// neighbours of their distances to their own k-th nearest other sample. ρ_i = ρ·h_i/h is kept
// within the cloud's bounding-box diagonal. With adaptive support, `merged` marks the samples
// whose supports hold too many (global support keeps every sample, as the paper).
// Throws Error for a width that is not a positive number.
SupportWidths support_widths(std::span<const vec3> points, const ProjectionParams& params);

}  // namespace pss
