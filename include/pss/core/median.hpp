// The median of a sample: the element at size/2 of its sorted order (the upper of the two
// middle ones for an even count), found in linear time; 0 for none.
#pragma once

#include <algorithm>
#include <cstddef>
#include <vector>

namespace pss {

template <class T>
T median_of(std::vector<T> values) {
  if (values.empty()) return T(0);
  const auto middle = values.begin() + std::ptrdiff_t(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  return *middle;
}

}  // namespace pss
