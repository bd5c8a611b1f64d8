// Headerless raw volumes (read_raw_volume). The format comes from the input's first
// kFormatBytes, the way a caller passes what the command line said, without the checks of
// parse_dims and parse_skip (the CLI target covers those): byte 0 the voxel type, byte 1
// bit 0 big-endian, then dims x y z and skip as little-endian int32 (any value, negative
// too). The rest is the file.
#include <cstring>

#include "fuzz_input.hpp"
#include "pss/io/volume_file.hpp"

namespace {

constexpr std::size_t kFormatBytes = 18;

std::int32_t int32_at(const std::uint8_t* p) {
  const std::uint32_t u = std::uint32_t(p[0]) | std::uint32_t(p[1]) << 8 | std::uint32_t(p[2]) << 16 |
                          std::uint32_t(p[3]) << 24;
  std::int32_t i;
  std::memcpy(&i, &u, sizeof i);
  return i;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace pss::fuzz;
  if (size < kFormatBytes) return 0;
  pss::RawVolumeFormat format;
  format.type = static_cast<pss::VoxelType>(data[0] % 8);
  format.big_endian = data[1] & 1;
  for (int a = 0; a < 3; ++a) format.dims[a] = int32_at(data + 2 + 4 * a);
  format.skip = int32_at(data + 14);
  fresh_folder();
  const auto path = write_file("input.raw", as_text(data + kFormatBytes, size - kFormatBytes));
  expect_value_or_error([&] { check_volume(pss::read_raw_volume(path, format)); });
  return 0;
}
