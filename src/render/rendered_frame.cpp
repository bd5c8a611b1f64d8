#include "pss/render/rendered_frame.hpp"

namespace pss {

FrameSummary summary_of_counts(const std::vector<std::uint16_t>& counts) {
  FrameSummary s;
  for (const std::uint16_t c : counts) s.add(c & 1, c & 2, c & 4, c >> 3);
  s.finish();
  return s;
}

}  // namespace pss
