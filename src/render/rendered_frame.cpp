#include "pss/render/rendered_frame.hpp"

namespace pss {

FrameSummary summary_of_counts(const std::vector<std::uint16_t>& counts, std::int64_t secondary_rays) {
  FrameSummary s;
  s.rays = std::int64_t(counts.size());
  s.secondary_rays = secondary_rays;
  std::int64_t iterations = 0;  // of the hits
  for (const std::uint16_t c : counts) {
    s.iterations += c >> 3;
    if (!(c & 1)) continue;
    ++s.hits;
    iterations += c >> 3;
    if (c & 2) ++s.converged;
    if (c & 4) ++s.capped;
  }
  s.mean_iterations = s.hits ? double(iterations) / double(s.hits) : 0.0;
  return s;
}

}  // namespace pss
