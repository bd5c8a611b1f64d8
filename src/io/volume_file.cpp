#include "pss/io/volume_file.hpp"

#include <zlib.h>

#include <algorithm>
#include <bit>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "pss/core/error.hpp"
#include "pss/io/output_file.hpp"
#include "bytes.hpp"
#include "volume_decode.hpp"

namespace pss {

namespace volume_io {

std::string trim(std::string_view s) {
  std::size_t b = 0, e = s.size();
  while (b < e && std::isspace(static_cast<unsigned char>(s[b]))) ++b;
  while (e > b && std::isspace(static_cast<unsigned char>(s[e - 1]))) --e;
  return std::string(s.substr(b, e - b));
}

std::string lower(std::string s) {
  for (char& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

bool parse_int64(std::string_view s, std::int64_t& out) {
  const std::string t = trim(s);
  const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), out);
  return ec == std::errc() && end == t.data() + t.size() && !t.empty();
}

bool parse_float(std::string_view s, float& out) {
  const std::string t = trim(s);
  if (t.empty()) return false;
  char* end = nullptr;
  out = std::strtof(t.c_str(), &end);
  return end == t.c_str() + t.size() && std::isfinite(out);
}

std::vector<std::string> split(std::string_view s, std::string_view separators) {
  std::vector<std::string> parts;
  std::string current;
  for (char c : s) {
    if (separators.find(c) != std::string_view::npos) {
      if (!current.empty()) parts.push_back(current);
      current.clear();
    } else {
      current += c;
    }
  }
  if (!current.empty()) parts.push_back(current);
  return parts;
}

std::string describe(ivec3 d) {
  return std::to_string(d.x) + "x" + std::to_string(d.y) + "x" + std::to_string(d.z);
}

std::int64_t checked_voxel_count(ivec3 dims, const std::string& where) {
  for (int a = 0; a < 3; ++a)
    if (dims[a] <= 0) throw Error(where + ": dimension " + std::to_string(dims[a]) + " is not positive");
  std::int64_t n = 1;
  bool overflow = false;
  for (int a = 0; a < 3; ++a) overflow = overflow || __builtin_mul_overflow(n, std::int64_t(dims[a]), &n);
  if (overflow || n > kMaxVoxels)
    throw Error(where + ": " + describe(dims) + " is " +
                (overflow ? std::string("more than 2^63") : std::to_string(n)) + " voxels, more than the " +
                std::to_string(kMaxVoxels) +
                " (2^31) pss reads: a read voxel takes 20 bytes (value, gradient, weight), 40 GiB at that cap");
  return n;
}

namespace {

template <class T>
void decode_as(const std::filesystem::path& path, const char* bytes, std::int64_t count, bool swap, float* out) {
  for (std::int64_t i = 0; i < count; ++i) {
    const T x = io::load<T>(bytes + sizeof(T) * i, swap);
    if constexpr (std::is_floating_point_v<T>) {
      // float64 beyond float's range becomes inf: as much an error as a stored NaN.
      const float f = static_cast<float>(x);
      if (!std::isfinite(f))
        throw file_error(path, "voxel " + std::to_string(i) + " is not a finite number" +
                                   (std::isfinite(x) ? " as a float" : ""));
      out[i] = f;
    } else {
      out[i] = static_cast<float>(x);  // int32/uint32 round to 24 bits of mantissa
    }
  }
}

}  // namespace

std::vector<float> decode(const std::filesystem::path& path, const char* bytes, std::int64_t count, VoxelType type,
                          bool big_endian) {
  std::vector<float> values(static_cast<std::size_t>(count));
  const bool swap = big_endian != (std::endian::native == std::endian::big);
  float* out = values.data();
  switch (type) {
    case VoxelType::int8: decode_as<std::int8_t>(path, bytes, count, swap, out); break;
    case VoxelType::uint8: decode_as<std::uint8_t>(path, bytes, count, swap, out); break;
    case VoxelType::int16: decode_as<std::int16_t>(path, bytes, count, swap, out); break;
    case VoxelType::uint16: decode_as<std::uint16_t>(path, bytes, count, swap, out); break;
    case VoxelType::int32: decode_as<std::int32_t>(path, bytes, count, swap, out); break;
    case VoxelType::uint32: decode_as<std::uint32_t>(path, bytes, count, swap, out); break;
    case VoxelType::float32: decode_as<float>(path, bytes, count, swap, out); break;
    case VoxelType::float64: decode_as<double>(path, bytes, count, swap, out); break;
  }
  return values;
}

// Exactly `expected` bytes from a gzip (or zlib) stream; a short or corrupt stream is an
// error. The output grows as the stream delivers bytes, so memory follows what the file
// holds, not what its header claims: a 200-byte stream claiming gigabytes costs kilobytes.
std::string inflate_exact(const std::filesystem::path& path, std::string_view compressed, std::size_t expected) {
  // Deflate expands at most 1032:1 (RFC 1951, a 258-byte match per 2 bits), so this much
  // room is enough for any honest stream and bounded by the file's size.
  constexpr std::size_t kMaxDeflateRatio = 1032;
  constexpr std::size_t piece = std::size_t(1) << 18;
  std::string out;
  out.reserve(std::min(expected, compressed.size() * kMaxDeflateRatio + piece));
  std::vector<char> buffer(piece);
  z_stream z{};
  if (inflateInit2(&z, 15 + 32) != Z_OK) throw file_error(path, "cannot initialise zlib");
  z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(compressed.data()));
  z.avail_in = 0;
  std::size_t in_left = compressed.size();
  // zlib counts in 32-bit uInt: feed the input in chunks.
  constexpr std::size_t chunk = std::size_t(1) << 30;
  int status = Z_OK;
  for (;;) {
    if (z.avail_in == 0 && in_left > 0) {
      z.avail_in = uInt(std::min(in_left, chunk));
      in_left -= z.avail_in;
    }
    z.next_out = reinterpret_cast<Bytef*>(buffer.data());
    z.avail_out = uInt(buffer.size());
    status = inflate(&z, Z_NO_FLUSH);
    const std::size_t got = buffer.size() - z.avail_out;
    if (got > expected - out.size()) {
      inflateEnd(&z);
      throw file_error(path, "gzip data holds more than the " + std::to_string(expected) + " bytes the header promises");
    }
    out.append(buffer.data(), got);
    if (status == Z_STREAM_END) break;
    if (status == Z_BUF_ERROR && z.avail_in == 0 && in_left > 0) continue;
    if (status != Z_OK) break;  // input exhausted (Z_BUF_ERROR) or corrupt
  }
  const std::size_t produced = out.size();
  inflateEnd(&z);
  if (status == Z_DATA_ERROR || status == Z_NEED_DICT || status == Z_MEM_ERROR)
    throw file_error(path, "corrupt gzip data");
  if (status != Z_STREAM_END) {
    if (produced < expected)
      throw file_error(path, "truncated gzip stream: " + std::to_string(produced) + " of " + std::to_string(expected) +
                                 " bytes");
    throw file_error(path, "truncated gzip stream (no end marker)");
  }
  if (produced < expected)
    throw file_error(path, "gzip data holds " + std::to_string(produced) + " bytes, the header promises " +
                               std::to_string(expected));
  return out;
}

std::filesystem::path beside(const std::filesystem::path& header, const std::string& name) {
  const std::filesystem::path p(name);
  return p.is_absolute() ? p : header.parent_path() / p;
}

}  // namespace volume_io

using namespace volume_io;

namespace {

// NRRD "(x,y,z)" vectors.
bool parse_vector(std::string_view s, vec3& out) {
  const std::string t = trim(s);
  if (t.size() < 2 || t.front() != '(' || t.back() != ')') return false;
  const auto parts = split(std::string_view(t).substr(1, t.size() - 2), ",");
  if (parts.size() != 3) return false;
  for (int a = 0; a < 3; ++a)
    if (!parse_float(parts[a], out[a])) return false;
  return true;
}

// Every spelling of the NRRD format's `type:` field for the types pss reads (NRRD spec,
// "type"); the 64-bit integers and "block" are not among them.
std::optional<VoxelType> nrrd_type(const std::string& t) {
  static const std::pair<const char*, VoxelType> names[] = {
      {"signed char", VoxelType::int8},        {"int8", VoxelType::int8},
      {"int8_t", VoxelType::int8},             {"uchar", VoxelType::uint8},
      {"unsigned char", VoxelType::uint8},     {"uint8", VoxelType::uint8},
      {"uint8_t", VoxelType::uint8},           {"short", VoxelType::int16},
      {"short int", VoxelType::int16},         {"signed short", VoxelType::int16},
      {"signed short int", VoxelType::int16},  {"int16", VoxelType::int16},
      {"int16_t", VoxelType::int16},           {"ushort", VoxelType::uint16},
      {"unsigned short", VoxelType::uint16},   {"unsigned short int", VoxelType::uint16},
      {"uint16", VoxelType::uint16},           {"uint16_t", VoxelType::uint16},
      {"int", VoxelType::int32},               {"signed int", VoxelType::int32},
      {"int32", VoxelType::int32},             {"int32_t", VoxelType::int32},
      {"uint", VoxelType::uint32},             {"unsigned int", VoxelType::uint32},
      {"uint32", VoxelType::uint32},           {"uint32_t", VoxelType::uint32},
      {"float", VoxelType::float32},           {"double", VoxelType::float64},
  };
  // Runs of blanks count as one ("unsigned  short").
  std::string key;
  for (const std::string& w : split(t, " \t")) key += (key.empty() ? "" : " ") + w;
  for (const auto& [name, type] : names)
    if (key == name) return type;
  return std::nullopt;
}

}  // namespace

const char* voxel_type_name(VoxelType t) {
  switch (t) {
    case VoxelType::int8: return "int8";
    case VoxelType::uint8: return "uint8";
    case VoxelType::int16: return "int16";
    case VoxelType::uint16: return "uint16";
    case VoxelType::int32: return "int32";
    case VoxelType::uint32: return "uint32";
    case VoxelType::float32: return "float32";
    case VoxelType::float64: return "float64";
  }
  return "?";
}

int voxel_type_size(VoxelType t) {
  switch (t) {
    case VoxelType::int8:
    case VoxelType::uint8: return 1;
    case VoxelType::int16:
    case VoxelType::uint16: return 2;
    case VoxelType::int32:
    case VoxelType::uint32:
    case VoxelType::float32: return 4;
    case VoxelType::float64: return 8;
  }
  return 1;
}

ivec3 parse_dims(std::string_view text) {
  const auto parts = split(text, "xX");
  ivec3 d(0);
  std::int64_t v[3];
  if (parts.size() != 3 || text.find_first_not_of("0123456789xX") != std::string_view::npos ||
      !parse_int64(parts[0], v[0]) || !parse_int64(parts[1], v[1]) || !parse_int64(parts[2], v[2]))
    throw Error("--dims " + quote(text) + ": expected XxYxZ, e.g. 64x64x64");
  for (int a = 0; a < 3; ++a) {
    if (v[a] <= 0) throw Error("--dims " + quote(text) + ": every dimension must be positive");
    if (v[a] > (std::int64_t(1) << 30)) throw Error("--dims " + quote(text) + ": dimension too large (overflow)");
    d[a] = int(v[a]);
  }
  checked_voxel_count(d, "--dims " + quote(text));
  return d;
}

vec3 parse_spacing(std::string_view text) {
  const auto parts = split(text, ",");
  vec3 s;
  if (parts.size() != 3 || !parse_float(parts[0], s.x) || !parse_float(parts[1], s.y) || !parse_float(parts[2], s.z) ||
      !(s.x > 0 && s.y > 0 && s.z > 0))
    throw Error("--spacing " + quote(text) + ": expected three positive numbers sx,sy,sz");
  return s;
}

VoxelType parse_voxel_type(std::string_view text) {
  for (VoxelType t : {VoxelType::int8, VoxelType::uint8, VoxelType::int16, VoxelType::uint16, VoxelType::int32,
                      VoxelType::uint32, VoxelType::float32, VoxelType::float64})
    if (text == voxel_type_name(t)) return t;
  throw Error("--type " + quote(text) +
              ": expected int8, uint8, int16, uint16, int32, uint32, float32 or float64");
}

std::int64_t parse_skip(std::string_view text) {
  std::int64_t n = 0;
  if (text.find_first_not_of("0123456789") != std::string_view::npos || !parse_int64(text, n) || n < 0 ||
      n > (std::int64_t(1) << 50))
    throw Error("--skip " + quote(text) + ": expected a byte count >= 0");
  return n;
}

namespace {

VolumeFile read_raw_file(const std::filesystem::path& path, const RawVolumeFormat& format) {
  const std::int64_t count = checked_voxel_count(format.dims, path.string());
  if (format.skip < 0) throw file_error(path, "negative --skip " + std::to_string(format.skip));
  // count <= 2^31, 8-byte voxels, skip <= 2^50 (parse_skip): no overflow.
  const std::int64_t voxel_bytes = count * voxel_type_size(format.type);
  const std::int64_t expected = format.skip + voxel_bytes;
  const auto mismatch = [&](std::uint64_t size) {
    return file_error(path, "holds " + std::to_string(size) + " bytes, but " +
                                (format.skip ? std::to_string(format.skip) + " skipped + " : std::string()) +
                                describe(format.dims) + " " + voxel_type_name(format.type) + " voxels need " +
                                std::to_string(expected));
  };
  // Compare the claim with the file's size before reading or allocating anything.
  std::error_code ec;
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (!ec && size != std::uintmax_t(expected)) throw mismatch(size);
  const std::string bytes = read_file(path);
  if (std::int64_t(bytes.size()) != expected) throw mismatch(bytes.size());
  VolumeFile f;
  f.volume.dims = format.dims;
  f.volume.spacing = format.spacing;
  f.volume.values = decode(path, bytes.data() + format.skip, count, format.type, format.big_endian);
  f.source = {"raw", format.type, format.big_endian, false, {}};
  return f;
}

VolumeFile read_nrrd_file(const std::filesystem::path& path) {
  const std::string file = read_file(path);
  std::size_t pos = 0;
  const auto next_line = [&](std::string& line) {
    if (pos >= file.size()) return false;
    std::size_t end = file.find('\n', pos);
    if (end == std::string::npos) end = file.size();
    line = file.substr(pos, end - pos);
    if (!line.empty() && line.back() == '\r') line.pop_back();
    pos = end + 1;
    return true;
  };
  std::string line;
  if (!next_line(line) || line.rfind("NRRD000", 0) != 0) throw file_error(path, "not a NRRD file (no NRRD000x magic)");

  std::optional<VoxelType> type;
  int dimension = 0;
  ivec3 dims(0);
  bool have_sizes = false;
  bool big_endian = false;
  bool gzip = false;
  vec3 spacing(1.0f), origin(0.0f);
  std::string data_file;
  std::int64_t byte_skip = 0;
  bool attached = true;
  while (next_line(line)) {
    if (line.empty()) break;  // end of the header; attached data follows
    if (line[0] == '#') continue;
    if (line.find(":=") != std::string::npos) continue;  // key/value pairs carry no geometry
    const std::size_t colon = line.find(": ");
    if (colon == std::string::npos) throw file_error(path, "malformed NRRD header line " + quote(line));
    const std::string field = lower(trim(line.substr(0, colon)));
    const std::string value = trim(line.substr(colon + 2));
    const auto bad = [&] { return file_error(path, "unsupported NRRD " + printable(field) + " " + quote(value)); };
    if (field == "type") {
      type = nrrd_type(lower(value));
      if (!type) throw bad();
    } else if (field == "dimension") {
      std::int64_t d;
      if (!parse_int64(value, d) || d != 3) throw bad();
      dimension = 3;
    } else if (field == "sizes") {
      const auto parts = split(value, " \t");
      std::int64_t v[3];
      if (parts.size() != 3 || !parse_int64(parts[0], v[0]) || !parse_int64(parts[1], v[1]) ||
          !parse_int64(parts[2], v[2]))
        throw bad();
      for (int a = 0; a < 3; ++a) {
        if (v[a] <= 0 || v[a] > (std::int64_t(1) << 30))
          throw file_error(path, "NRRD sizes " + quote(value) + ": every size must be positive and not overflow");
        dims[a] = int(v[a]);
      }
      checked_voxel_count(dims, path.string());
      have_sizes = true;
    } else if (field == "endian") {
      if (value == "little") big_endian = false;
      else if (value == "big") big_endian = true;
      else throw bad();
    } else if (field == "encoding") {
      const std::string e = lower(value);
      if (e == "raw") gzip = false;
      else if (e == "gzip" || e == "gz") gzip = true;
      else throw bad();
    } else if (field == "spacings") {
      const auto parts = split(value, " \t");
      if (parts.size() != 3) throw bad();
      for (int a = 0; a < 3; ++a)
        if (!parse_float(parts[a], spacing[a]) || !(spacing[a] > 0)) throw bad();
    } else if (field == "space directions") {
      // Only axis-aligned grids: the directions must form a positive diagonal.
      const auto parts = split(value, " \t");
      if (parts.size() != 3) throw bad();
      for (int a = 0; a < 3; ++a) {
        vec3 d;
        if (!parse_vector(parts[a], d)) throw bad();
        for (int b = 0; b < 3; ++b)
          if (b != a && d[b] != 0) throw file_error(path, "unsupported NRRD space directions " + quote(value) + " (only diagonal)");
        if (!(d[a] > 0)) throw file_error(path, "unsupported NRRD space directions " + quote(value) + " (only positive diagonal)");
        spacing[a] = d[a];
      }
    } else if (field == "space origin") {
      if (!parse_vector(value, origin)) throw bad();
    } else if (field == "data file" || field == "datafile") {
      if (value.find('%') != std::string::npos || value.rfind("LIST", 0) == 0) throw bad();
      data_file = value;
      attached = false;
    } else if (field == "byte skip") {
      if (!parse_int64(value, byte_skip) || byte_skip < -1) throw bad();
    } else if (field == "space" || field == "space dimension" || field == "content" || field == "kinds" ||
               field == "labels" || field == "units" || field == "space units" || field == "centers" ||
               field == "centerings" || field == "min" || field == "max" || field == "old min" || field == "old max") {
      // Descriptive only: they change nothing about where the voxels are.
    } else {
      throw file_error(path, "unsupported NRRD field " + quote(field));
    }
  }
  if (!type) throw file_error(path, "NRRD header has no type");
  if (dimension != 3) throw file_error(path, "NRRD header has no 'dimension: 3'");
  if (!have_sizes) throw file_error(path, "NRRD header has no sizes");
  if (byte_skip == -1 && gzip) throw file_error(path, "unsupported NRRD byte skip -1 with gzip encoding");

  const std::int64_t count = std::int64_t(dims.x) * dims.y * dims.z;
  const std::size_t expected = std::size_t(count) * std::size_t(voxel_type_size(*type));
  std::string detached;
  std::filesystem::path data_path = path;
  std::string_view data;
  if (attached) {
    data = std::string_view(file).substr(std::min(pos, file.size()));
  } else {
    data_path = beside(path, data_file);
    detached = read_file(data_path);
    data = detached;
  }
  std::string inflated;
  if (gzip) {
    inflated = inflate_exact(data_path, data, expected + std::size_t(byte_skip));
    data = std::string_view(inflated).substr(std::size_t(byte_skip));
  } else if (byte_skip == -1) {
    if (data.size() < expected)
      throw file_error(data_path, "holds " + std::to_string(data.size()) + " bytes of data, the header needs " +
                                      std::to_string(expected));
    data = data.substr(data.size() - expected);
  } else {
    if (data.size() != expected + std::size_t(byte_skip))
      throw file_error(data_path, "holds " + std::to_string(data.size()) + " bytes of data, the header needs " +
                                      std::to_string(expected + std::size_t(byte_skip)));
    data = data.substr(std::size_t(byte_skip));
  }
  VolumeFile f;
  f.volume.dims = dims;
  f.volume.spacing = spacing;
  f.volume.origin = origin;
  f.volume.values = decode(data_path, data.data(), count, *type, big_endian);
  f.source = {"NRRD", *type, big_endian, gzip, {}};
  return f;
}

}  // namespace

Volume read_raw_volume(const std::filesystem::path& path, const RawVolumeFormat& format) {
  return read_raw_file(path, format).volume;
}

Volume read_nrrd(const std::filesystem::path& path) { return read_nrrd_file(path).volume; }

namespace {

enum class HeadedFormat { none, nrrd, metaimage, nifti };

HeadedFormat headed_format(const std::filesystem::path& path) {
  const std::string name = lower(path.filename().string());
  const auto ends_with = [&](std::string_view suffix) {
    return name.size() > suffix.size() && name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0;
  };
  if (ends_with(".nrrd") || ends_with(".nhdr")) return HeadedFormat::nrrd;
  if (ends_with(".mhd") || ends_with(".mha")) return HeadedFormat::metaimage;
  if (ends_with(".nii") || ends_with(".nii.gz")) return HeadedFormat::nifti;
  return HeadedFormat::none;
}

}  // namespace

bool has_volume_header(const std::filesystem::path& path) { return headed_format(path) != HeadedFormat::none; }

VolumeFile read_volume_file(const std::filesystem::path& path, const std::optional<RawVolumeFormat>& raw) {
  const HeadedFormat format = headed_format(path);
  if (format != HeadedFormat::none && raw)
    throw Error(path.string() + ": the file's header describes the volume; drop --dims/--type/--spacing/--endian/--skip");
  switch (format) {
    case HeadedFormat::nrrd: return read_nrrd_file(path);
    case HeadedFormat::metaimage: return read_metaimage_file(path);
    case HeadedFormat::nifti: return read_nifti_file(path);
    case HeadedFormat::none: break;
  }
  if (!raw)
    throw Error(path.string() +
                ": not .nrrd/.nhdr/.mhd/.mha/.nii/.nii.gz, so a raw volume: it needs --dims XxYxZ (and --type unless uint8)");
  return read_raw_file(path, *raw);
}

Volume read_volume(const std::filesystem::path& path, const std::optional<RawVolumeFormat>& raw) {
  return read_volume_file(path, raw).volume;
}

}  // namespace pss
