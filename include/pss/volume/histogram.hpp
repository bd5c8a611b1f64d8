// A volume's value statistics and histogram, and the iso-values its histogram suggests:
// the valleys between the main peaks, where one material (air, soft tissue, bone, metal)
// gives way to the next, for `pss info` and anyone choosing --iso.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace pss {

struct ValueStats {
  std::int64_t count = 0;
  float min = 0, max = 0;
  double mean = 0;
};

ValueStats value_stats(std::span<const float> values);

// `counts.size()` bins of equal width covering [lo, hi]; a value v falls in bin
// floor((v - lo) / width), the top edge into the last bin, values outside are not counted.
struct Histogram {
  float lo = 0, hi = 0;
  std::vector<std::int64_t> counts;

  int bins() const { return int(counts.size()); }
  double width() const { return (double(hi) - double(lo)) / double(counts.size()); }
  double edge(int b) const { return lo + width() * b; }  // lower edge of bin b; edge(bins()) = hi
  double center(int b) const { return lo + width() * (b + 0.5); }
  std::int64_t total() const;
};

// Throws nothing: lo == hi (a constant volume) gives every value in bin 0.
Histogram make_histogram(std::span<const float> values, int bins, float lo, float hi);

// The bins that suit the values for finding peaks: one per integer when the values are all
// integers spanning at most `max_bins` of them (8-bit data), else `max_bins` over [min, max].
Histogram fine_histogram(std::span<const float> values, const ValueStats& stats, int max_bins = 256);

// A valley between two main peaks of the histogram: `iso` separates the material of the
// lower peak from that of the upper one. With `tail`, there was one main peak only and
// `iso` is where it ends, at its foot: one of the two "peaks" is then the far end of the
// range, and its share the voxels in the tail beyond the foot (a plume in air, say).
struct IsoSuggestion {
  float iso;                        // the valley's value
  float lower_peak, upper_peak;     // the two peaks' values
  double lower_share, upper_share;  // fraction of all voxels in each peak's basin
  bool tail = false;
};

// Peaks holding at least `min_share` of the voxels, separated by valleys lower than
// `max_valley_ratio` times the lower of their two peaks; see histogram.cpp for the rule.
std::vector<IsoSuggestion> suggest_iso_values(const Histogram& fine, double min_share = 0.01,
                                              double max_valley_ratio = 0.5);
std::vector<IsoSuggestion> suggest_iso_values(std::span<const float> values);

}  // namespace pss
