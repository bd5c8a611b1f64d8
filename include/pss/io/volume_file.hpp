// Reading volumes, the forms CT and MRI data come in:
//   raw       headerless, described on the command line (--dims, --type, --spacing, --endian,
//             --skip);
//   NRRD      .nrrd with attached data, .nhdr with a detached 'data file', raw or gzip;
//   MetaImage .mhd with a detached ElementDataFile, .mha with LOCAL data, raw or zlib;
//   NIfTI-1   .nii and .nii.gz, read with the NIfTI reference library (niftiio).
// Voxels of any type below become float: int32, uint32 and float64 values lose precision
// beyond float's 24-bit mantissa (pss interpolates and thresholds them, it never needs the
// exact integers back). Every problem is a one-line pss::Error naming the file; nothing is
// returned half-read; a voxel that is not a finite float is an error.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

#include "pss/volume/volume.hpp"

namespace pss {

enum class VoxelType { int8, uint8, int16, uint16, int32, uint32, float32, float64 };

const char* voxel_type_name(VoxelType type);  // "int8" ... "float64", as --type spells them
int voxel_type_size(VoxelType type);          // bytes

// How to read a headerless raw file, x fastest.
struct RawVolumeFormat {
  ivec3 dims{0};
  VoxelType type = VoxelType::uint8;
  vec3 spacing{1.0f};
  bool big_endian = false;
  std::int64_t skip = 0;  // header bytes before the voxels; the file holds exactly skip + voxels
};

// Command-line spellings; each throws a one-line Error naming the flag's problem.
ivec3 parse_dims(std::string_view text);            // "64x64x64": positive, product <= 2^31 voxels
vec3 parse_spacing(std::string_view text);          // "1,1,2.5": positive and finite
VoxelType parse_voxel_type(std::string_view text);  // int8 | uint8 | int16 | ... | float64
std::int64_t parse_skip(std::string_view text);     // a byte count >= 0

// What the file said about its voxels before they became floats (for `pss info`).
struct VolumeSource {
  std::string format;  // "raw", "NRRD", "MetaImage", "NIfTI-1"
  VoxelType type = VoxelType::uint8;
  bool big_endian = false;  // byte order on disk (meaningless for 1-byte types)
  bool compressed = false;  // gzip / zlib
  std::string note;         // e.g. NIfTI's value scaling; empty when there is none
};

struct VolumeFile {
  Volume volume;
  VolumeSource source;
};

Volume read_raw_volume(const std::filesystem::path& path, const RawVolumeFormat& format);
Volume read_nrrd(const std::filesystem::path& path);
Volume read_metaimage(const std::filesystem::path& path);  // .mhd or .mha
Volume read_nifti(const std::filesystem::path& path);      // .nii or .nii.gz

// True for the extensions whose header describes the volume (any case): .nrrd .nhdr .mhd
// .mha .nii .nii.gz.
bool has_volume_header(const std::filesystem::path& path);

// Dispatches on the extension: a headed format, and then `raw` must be empty (the header
// says it all); anything else is a raw file and needs `raw`.
VolumeFile read_volume_file(const std::filesystem::path& path, const std::optional<RawVolumeFormat>& raw);
Volume read_volume(const std::filesystem::path& path, const std::optional<RawVolumeFormat>& raw);

}  // namespace pss
