// Reading volumes: raw files described on the command line (--dims, --type, --spacing,
// --endian) and NRRD (.nrrd with attached data, .nhdr with a detached 'data file'), raw or
// gzip encoded. Every problem is a one-line pss::Error; nothing is returned half-read.
#pragma once

#include <filesystem>
#include <optional>
#include <string_view>

#include "pss/volume/volume.hpp"

namespace pss {

enum class VoxelType { uint8, uint16, float32 };

// How to read a headerless raw file, x fastest.
struct RawVolumeFormat {
  ivec3 dims{0};
  VoxelType type = VoxelType::uint8;
  vec3 spacing{1.0f};
  bool big_endian = false;
};

// Command-line spellings; each throws a one-line Error naming the flag's problem.
ivec3 parse_dims(std::string_view text);        // "64x64x64": positive, product < 2^40 voxels
vec3 parse_spacing(std::string_view text);      // "1,1,2.5": positive and finite
VoxelType parse_voxel_type(std::string_view text);  // uint8 | uint16 | float32

Volume read_raw_volume(const std::filesystem::path& path, const RawVolumeFormat& format);
Volume read_nrrd(const std::filesystem::path& path);

// .nrrd and .nhdr (any case) are NRRD, and then `raw` must be empty (the header says it
// all); anything else is a raw file and needs `raw`.
Volume read_volume(const std::filesystem::path& path, const std::optional<RawVolumeFormat>& raw);

}  // namespace pss
