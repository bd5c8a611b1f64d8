#include "pss/volume/histogram.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace pss {

ValueStats value_stats(std::span<const float> values) {
  ValueStats s;
  s.count = std::int64_t(values.size());
  if (values.empty()) return s;
  s.min = s.max = values[0];
  double sum = 0;
  for (float v : values) {
    s.min = std::min(s.min, v);
    s.max = std::max(s.max, v);
    sum += v;
  }
  s.mean = sum / double(values.size());
  return s;
}

std::int64_t Histogram::total() const { return std::accumulate(counts.begin(), counts.end(), std::int64_t(0)); }

Histogram make_histogram(std::span<const float> values, int bins, float lo, float hi) {
  Histogram h;
  h.lo = lo;
  h.hi = hi;
  h.counts.assign(std::size_t(std::max(bins, 1)), 0);
  const int n = h.bins();
  const double scale = hi > lo ? n / (double(hi) - double(lo)) : 0.0;
  for (float v : values) {
    if (!(v >= lo && v <= hi)) continue;
    const int b = std::min(int((double(v) - lo) * scale), n - 1);
    ++h.counts[std::size_t(b)];
  }
  return h;
}

Histogram fine_histogram(std::span<const float> values, const ValueStats& stats, int max_bins) {
  const double span = double(stats.max) - double(stats.min);
  bool integers = span + 1 <= max_bins;
  for (std::size_t i = 0; integers && i < values.size(); ++i) integers = values[i] == std::floor(values[i]);
  if (integers) return make_histogram(values, int(span) + 1, stats.min - 0.5f, stats.max + 0.5f);
  return make_histogram(values, max_bins, stats.min, stats.max);
}

namespace {

// The bin of the lowest value strictly between bins a and b (a < b - 1); among equal lowest
// values (an empty gap) the middle of the first such run, so that a gap between two
// materials is split in its middle.
int valley_between(const std::vector<double>& s, int a, int b) {
  int lo = a + 1;
  for (int i = a + 1; i < b; ++i)
    if (s[i] < s[lo]) lo = i;
  int end = lo;
  while (end + 1 < b && s[end + 1] == s[lo]) ++end;
  return (lo + end) / 2;
}

}  // namespace

// The rule. A material fills a hump of the histogram; between two materials the histogram
// sinks, and the bottom of that valley is the value their boundary passes through: the iso-
// value that separates them. Sampling noise makes fine histograms ragged, so
//  1. the counts are smoothed with a Gaussian of σ = 2 bins of 256 (at least one bin);
//  2. every local maximum of the smoothed counts is a candidate peak (outside the range
//     counts are 0, so a material at the very end of the range, e.g. air at 0, is a peak);
//  3. peaks are merged away until every remaining one is significant: first the peak whose
//     basin (the bins between its two neighbouring valleys) holds the fewest voxels, while
//     that is under `min_share` of them; then, for the valley that is shallowest relative to
//     the lower of its two peaks, the lower peak, while that valley is above
//     `max_valley_ratio` times it (not notably lower than both peaks);
//  4. the valleys between the remaining peaks are the suggestions;
//  5. with one main peak left but `min_share` of the voxels beyond its foot on one side
//     (the first bin where the smoothed counts fall under 1 % of the peak's), that foot is
//     the suggestion: data such as a fuel plume or a smoke cloud have no second hump, yet
//     their surface is where the background ends.
// Removing a peak recomputes the valleys beside it as the minimum between the new
// neighbours, so merges never leave a valley that is not the lowest point between its peaks.
std::vector<IsoSuggestion> suggest_iso_values(const Histogram& fine, double min_share, double max_valley_ratio) {
  const int n = fine.bins();
  const double total = double(fine.total());
  if (n < 3 || total <= 0) return {};
  const double sigma = std::max(1.0, 2.0 * n / 256.0);
  const int radius = int(std::ceil(3 * sigma));
  std::vector<double> kernel(std::size_t(2 * radius + 1));
  for (int k = -radius; k <= radius; ++k) kernel[std::size_t(k + radius)] = std::exp(-0.5 * k * k / (sigma * sigma));
  std::vector<double> s(std::size_t(n), 0.0);
  for (int b = 0; b < n; ++b)
    for (int k = -radius; k <= radius; ++k)
      if (b + k >= 0 && b + k < n) s[b] += kernel[std::size_t(k + radius)] * double(fine.counts[std::size_t(b + k)]);

  std::vector<int> peaks;
  for (int b = 0; b < n; ++b) {
    const double left = b > 0 ? s[b - 1] : 0.0, right = b + 1 < n ? s[b + 1] : 0.0;
    if (s[b] > left && s[b] >= right) peaks.push_back(b);
  }

  std::vector<int> valleys;
  std::vector<double> share;
  const auto measure = [&] {
    valleys.clear();
    for (std::size_t i = 0; i + 1 < peaks.size(); ++i) valleys.push_back(valley_between(s, peaks[i], peaks[i + 1]));
    share.assign(peaks.size(), 0.0);
    for (std::size_t i = 0; i < peaks.size(); ++i) {
      const int from = i == 0 ? 0 : valleys[i - 1] + 1, to = i + 1 < peaks.size() ? valleys[i] : n - 1;
      for (int b = from; b <= to; ++b) share[i] += double(fine.counts[std::size_t(b)]);
      share[i] /= total;
    }
  };
  while (peaks.size() > 1) {
    measure();
    const std::size_t smallest = std::size_t(std::min_element(share.begin(), share.end()) - share.begin());
    if (share[smallest] < min_share) {
      peaks.erase(peaks.begin() + std::ptrdiff_t(smallest));
      continue;
    }
    std::size_t shallowest = 0;
    double worst = -1;
    for (std::size_t i = 0; i < valleys.size(); ++i) {
      const double ratio = s[valleys[i]] / std::min(s[peaks[i]], s[peaks[i + 1]]);
      if (ratio > worst) worst = ratio, shallowest = i;
    }
    if (worst <= max_valley_ratio) break;
    const std::size_t lower = s[peaks[shallowest]] < s[peaks[shallowest + 1]] ? shallowest : shallowest + 1;
    peaks.erase(peaks.begin() + std::ptrdiff_t(lower));
  }
  measure();

  std::vector<IsoSuggestion> out;
  if (peaks.size() == 1) {
    const int p = peaks[0];
    int up = p, down = p;
    while (up + 1 < n && s[up] >= 0.01 * s[p]) ++up;
    while (down > 0 && s[down] >= 0.01 * s[p]) --down;
    double above = 0, below = 0;
    for (int b = up; b < n; ++b) above += double(fine.counts[std::size_t(b)]);
    for (int b = 0; b <= down; ++b) below += double(fine.counts[std::size_t(b)]);
    // A foot only where the counts do fall under 1 % within the range.
    above = s[up] < 0.01 * s[p] ? above / total : 0;
    below = s[down] < 0.01 * s[p] ? below / total : 0;
    if (std::max(above, below) >= min_share) {
      if (above >= below)
        out.push_back({float(fine.center(up)), float(fine.center(p)), float(fine.center(n - 1)), 1 - above, above, true});
      else
        out.push_back({float(fine.center(down)), float(fine.center(0)), float(fine.center(p)), below, 1 - below, true});
    }
    return out;
  }
  for (std::size_t i = 0; i < valleys.size(); ++i)
    out.push_back({float(fine.center(valleys[i])), float(fine.center(peaks[i])), float(fine.center(peaks[i + 1])),
                   share[i], share[i + 1]});
  return out;
}

std::vector<IsoSuggestion> suggest_iso_values(std::span<const float> values) {
  if (values.empty()) return {};
  return suggest_iso_values(fine_histogram(values, value_stats(values)));
}

}  // namespace pss
