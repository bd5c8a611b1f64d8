// The values at a list of indices, in the list's order: what a step that works on a subset
// of the points (the orientation's tree over the points that stand for themselves) takes.
#pragma once

#include <cstddef>
#include <span>
#include <vector>

namespace pss {

template <class T>
std::vector<T> gathered(std::span<const T> values, std::span<const int> at) {
  std::vector<T> out(at.size());
  for (std::size_t k = 0; k < at.size(); ++k) out[k] = values[std::size_t(at[k])];
  return out;
}

}  // namespace pss
