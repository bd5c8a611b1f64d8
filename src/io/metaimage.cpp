// MetaImage (ITK's MetaIO): a text header of `Key = Value` lines ending with
// ElementDataFile, whose value is LOCAL when the voxels follow the header in the same file
// (.mha) or the name of a raw file beside the header (.mhd). Fields pss does not need are
// skipped, as MetaIO itself does (writers add their own); those that change which voxels
// are where are read or refused.
#include <cmath>
#include <optional>
#include <string>

#include "pss/core/error.hpp"
#include "pss/io/output_file.hpp"
#include "pss/io/volume_file.hpp"
#include "volume_decode.hpp"

namespace pss::volume_io {

namespace {

std::optional<VoxelType> met_type(const std::string& t) {
  if (t == "MET_CHAR") return VoxelType::int8;
  if (t == "MET_UCHAR") return VoxelType::uint8;
  if (t == "MET_SHORT") return VoxelType::int16;
  if (t == "MET_USHORT") return VoxelType::uint16;
  if (t == "MET_INT" || t == "MET_LONG") return VoxelType::int32;  // MetaIO's LONG is 4 bytes
  if (t == "MET_UINT" || t == "MET_ULONG") return VoxelType::uint32;
  if (t == "MET_FLOAT") return VoxelType::float32;
  if (t == "MET_DOUBLE") return VoxelType::float64;
  return std::nullopt;
}

}  // namespace

VolumeFile read_metaimage_file(const std::filesystem::path& path) {
  const std::string file = read_file(path);
  std::size_t pos = 0;
  std::optional<std::int64_t> ndims;
  std::optional<ivec3> dims;
  std::optional<VoxelType> type;
  std::optional<vec3> spacing, size;
  vec3 origin(0.0f);
  bool big_endian = false, compressed = false;
  std::int64_t header_size = 0;
  std::optional<std::int64_t> compressed_size;
  std::optional<std::string> data_file;

  while (pos < file.size() && !data_file) {
    std::size_t end = file.find('\n', pos);
    if (end == std::string::npos) end = file.size();
    std::string line = file.substr(pos, end - pos);
    pos = end + 1;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (trim(line).empty()) continue;
    const std::size_t eq = line.find('=');
    if (eq == std::string::npos) {
      throw file_error(path, "not a MetaImage header: line " + quote(line) + " has no '='");
    }
    const std::string key = lower(trim(line.substr(0, eq)));
    const std::string value = trim(line.substr(eq + 1));
    const auto bad = [&](const std::string& why = "") {
      return file_error(path, "MetaImage " + printable(trim(line.substr(0, eq))) + " " + quote(value) +
                                  (why.empty() ? " is not valid" : ": " + why));
    };
    const auto three_floats = [&] {
      const auto parts = split(value, " \t");
      vec3 v;
      if (parts.size() != 3 || !parse_float(parts[0], v.x) || !parse_float(parts[1], v.y) ||
          !parse_float(parts[2], v.z))
        throw bad("expected three numbers");
      return v;
    };
    const auto boolean = [&] {
      const std::string b = lower(value);
      if (b == "true" || b == "1") return true;
      if (b == "false" || b == "0") return false;
      throw bad("expected True or False");
    };
    if (key == "objecttype") {
      if (lower(value) != "image") throw bad("only Image objects hold volumes");
    } else if (key == "ndims") {
      std::int64_t n;
      if (!parse_int64(value, n)) throw bad();
      if (n != 3) throw bad("pss reads 3-D volumes only");
      ndims = n;
    } else if (key == "dimsize") {
      const auto parts = split(value, " \t");
      std::int64_t v[3];
      if (parts.size() != 3 || !parse_int64(parts[0], v[0]) || !parse_int64(parts[1], v[1]) ||
          !parse_int64(parts[2], v[2]))
        throw bad("expected three sizes");
      ivec3 d;
      for (int a = 0; a < 3; ++a) {
        if (v[a] <= 0 || v[a] > (std::int64_t(1) << 30)) throw bad("every size must be positive and not overflow");
        d[a] = int(v[a]);
      }
      checked_voxel_count(d, path.string());
      dims = d;
    } else if (key == "elementtype") {
      type = met_type(value);
      if (!type) throw bad("expected MET_CHAR, MET_UCHAR, MET_SHORT, MET_USHORT, MET_INT, MET_UINT, MET_FLOAT or MET_DOUBLE");
    } else if (key == "elementspacing" || key == "elementsize") {
      const vec3 v = three_floats();
      if (!(v.x > 0 && v.y > 0 && v.z > 0)) throw bad("expected three positive numbers");
      (key == "elementspacing" ? spacing : size) = v;
    } else if (key == "offset" || key == "origin" || key == "position") {
      origin = three_floats();
    } else if (key == "binarydatabyteordermsb" || key == "elementbyteordermsb") {
      big_endian = boolean();
    } else if (key == "binarydata") {
      if (!boolean()) throw bad("ASCII voxel data is not supported");
    } else if (key == "compresseddata") {
      compressed = boolean();
    } else if (key == "compresseddatasize") {
      std::int64_t n;
      if (!parse_int64(value, n) || n < 0) throw bad();
      compressed_size = n;
    } else if (key == "headersize") {
      if (!parse_int64(value, header_size) || header_size < -1) throw bad("expected a byte count, or -1");
    } else if (key == "elementnumberofchannels") {
      std::int64_t n;
      if (!parse_int64(value, n) || n != 1) throw bad("pss reads scalar volumes (1 channel) only");
    } else if (key == "transformmatrix" || key == "rotation" || key == "orientation") {
      // pss grids are axis-aligned: a rotated or flipped one would be drawn wrongly, so
      // only the identity passes.
      const auto parts = split(value, " \t");
      float m[9];
      bool identity = parts.size() == 9;
      for (int i = 0; identity && i < 9; ++i)
        identity = parse_float(parts[i], m[i]) && std::abs(m[i] - (i % 4 == 0 ? 1.0f : 0.0f)) < 1e-6f;
      if (!identity) throw bad("only the identity is supported (axis-aligned grids)");
    } else if (key == "elementdatafile") {
      if (value.empty()) throw bad();
      const std::string v = lower(value);
      if (v == "list" || v.rfind("list ", 0) == 0 || value.find('%') != std::string::npos)
        throw bad("lists and patterns of slice files are not supported");
      data_file = value;
    }
    // Anything else (Comment, AnatomicalOrientation, CenterOfRotation, ElementMin, ...)
    // says nothing about where the voxels are.
  }
  if (!data_file) throw file_error(path, "not a MetaImage header: no ElementDataFile line");
  if (!ndims) throw file_error(path, "MetaImage header has no NDims");
  if (!dims) throw file_error(path, "MetaImage header has no DimSize");
  if (!type) throw file_error(path, "MetaImage header has no ElementType");
  if (compressed && header_size == -1) throw file_error(path, "MetaImage HeaderSize -1 with CompressedData is not supported");

  const std::int64_t count = checked_voxel_count(*dims, path.string());
  const std::size_t expected = std::size_t(count) * std::size_t(voxel_type_size(*type));
  std::filesystem::path data_path = path;
  std::string detached;
  std::string_view data;
  if (lower(*data_file) == "local") {
    data = std::string_view(file).substr(std::min(pos, file.size()));
  } else {
    data_path = beside(path, *data_file);
    detached = read_file(data_path);
    data = detached;
  }
  if (header_size > 0) {
    if (std::size_t(header_size) > data.size())
      throw file_error(data_path, "MetaImage HeaderSize " + std::to_string(header_size) + " is beyond the " +
                                      std::to_string(data.size()) + " bytes of data");
    data = data.substr(std::size_t(header_size));
  }
  std::string inflated;
  if (compressed) {
    if (compressed_size && std::size_t(*compressed_size) != data.size())
      throw file_error(data_path, "holds " + std::to_string(data.size()) + " bytes of compressed data, the header says " +
                                      std::to_string(*compressed_size));
    inflated = inflate_exact(data_path, data, expected);
    data = inflated;
  } else if (header_size == -1) {  // MetaIO: the voxels are the file's last bytes
    if (data.size() < expected)
      throw file_error(data_path, "holds " + std::to_string(data.size()) + " bytes of data, the header needs " +
                                      std::to_string(expected));
    data = data.substr(data.size() - expected);
  } else if (data.size() != expected) {
    throw file_error(data_path, "holds " + std::to_string(data.size()) + " bytes of data, " + describe(*dims) + " " +
                                    voxel_type_name(*type) + " voxels need " + std::to_string(expected));
  }
  VolumeFile f;
  f.volume.dims = *dims;
  f.volume.spacing = spacing ? *spacing : size ? *size : vec3(1.0f);
  f.volume.origin = origin;
  f.volume.values = decode(data_path, data.data(), count, *type, big_endian);
  f.source = {"MetaImage", *type, big_endian, compressed, {}};
  return f;
}

}  // namespace pss::volume_io

namespace pss {

Volume read_metaimage(const std::filesystem::path& path) { return volume_io::read_metaimage_file(path).volume; }

}  // namespace pss
