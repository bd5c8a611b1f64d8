// What the volume readers (volume_file.cpp, metaimage.cpp, nifti.cpp) share: header text
// helpers, size checks, the voxel decoder and the zlib/gzip inflater. Internal to src/io.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "pss/io/volume_file.hpp"

namespace pss::volume_io {

// The most voxels pss reads: 2^31. Once read, a voxel costs 20 bytes (its float value, a
// vec3 gradient and a feature weight), so this cap is 40 GiB of fields, past any
// workstation's memory and past the 2048^2 x 512 CT scans pss is meant for. It also keeps
// every byte count (voxels x 8-byte type + a skip of up to 2^50) far from 64-bit overflow.
constexpr std::int64_t kMaxVoxels = std::int64_t(1) << 31;

std::string trim(std::string_view s);
std::string lower(std::string s);
bool parse_int64(std::string_view s, std::int64_t& out);
bool parse_float(std::string_view s, float& out);  // finite only
std::vector<std::string> split(std::string_view s, std::string_view separators);
std::string describe(ivec3 dims);  // "2x3x4"

// Throws unless the dims are positive and their product (in voxels) is at most kMaxVoxels;
// the product is overflow-checked, so any three ints give the right answer.
std::int64_t checked_voxel_count(ivec3 dims, const std::string& where);

// Decodes `count` voxels of `type` into floats; a voxel that is not finite as a float is an
// error naming `path`.
std::vector<float> decode(const std::filesystem::path& path, const char* bytes, std::int64_t count, VoxelType type,
                          bool big_endian);

// Exactly `expected` bytes from a gzip or zlib stream (detected from its header); a short
// or corrupt stream is an error, trailing data after the stream's end too. The output
// grows as the stream delivers it: a header's claim allocates nothing by itself.
std::string inflate_exact(const std::filesystem::path& path, std::string_view compressed, std::size_t expected);

// The path of a detached data file named in a header: relative to the header's folder.
std::filesystem::path beside(const std::filesystem::path& header, const std::string& name);

// The readers of metaimage.cpp and nifti.cpp, behind read_volume_file's dispatch.
VolumeFile read_metaimage_file(const std::filesystem::path& path);
VolumeFile read_nifti_file(const std::filesystem::path& path);

}  // namespace pss::volume_io
