// The readers' colour channels: whatever a file stores becomes 0..255 (PointCloud::colors).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace pss::io {

// 0..1 (OBJ, float PLY colours); outside clamps, NaN is 0.
inline std::uint8_t channel_from_unit(double v) {
  return v > 0 ? static_cast<std::uint8_t>(std::lround(std::min(v, 1.0) * 255)) : 0;
}

// 0..65535 (LAS, ushort PLY colours), rounded: 65535 → 255, 257 → 1.
inline std::uint8_t channel_from_16bit(std::uint32_t v) {
  return static_cast<std::uint8_t>((std::min(v, 65535u) * 255 + 32767) / 65535);
}

}  // namespace pss::io
