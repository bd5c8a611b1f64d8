#include "pss/io/volume_file.hpp"

#include <zlib.h>

#include <algorithm>
#include <bit>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "pss/core/error.hpp"
#include "pss/io/output_file.hpp"
#include "bytes.hpp"

namespace pss {

namespace {

// More voxels than this is not a volume we could hold; also keeps every size product far
// from overflowing 64 bits.
constexpr std::int64_t kMaxVoxels = std::int64_t(1) << 40;

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

// Throws unless the dims are positive and their product (in voxels) is sane.
std::int64_t checked_voxel_count(ivec3 dims, const std::string& where) {
  std::int64_t n = 1;
  for (int a = 0; a < 3; ++a) {
    if (dims[a] <= 0) throw Error(where + ": dimension " + std::to_string(dims[a]) + " is not positive");
    n *= dims[a];
    if (n > kMaxVoxels) throw Error(where + ": " + std::to_string(dims.x) + "x" + std::to_string(dims.y) + "x" +
                                    std::to_string(dims.z) + " voxels is too many (overflow)");
  }
  return n;
}

int type_size(VoxelType t) { return t == VoxelType::uint8 ? 1 : t == VoxelType::uint16 ? 2 : 4; }

// Decodes `count` voxels of `type` into floats; non-finite floats are an error.
std::vector<float> decode(const std::filesystem::path& path, const char* bytes, std::int64_t count, VoxelType type,
                          bool big_endian) {
  std::vector<float> values(static_cast<std::size_t>(count));
  const bool swap = big_endian != (std::endian::native == std::endian::big);
  switch (type) {
    case VoxelType::uint8:
      for (std::int64_t i = 0; i < count; ++i) values[i] = float(static_cast<unsigned char>(bytes[i]));
      break;
    case VoxelType::uint16:
      for (std::int64_t i = 0; i < count; ++i) values[i] = float(io::load<std::uint16_t>(bytes + 2 * i, swap));
      break;
    case VoxelType::float32:
      for (std::int64_t i = 0; i < count; ++i) {
        const float f = io::load<float>(bytes + 4 * i, swap);
        if (!std::isfinite(f)) throw file_error(path, "voxel " + std::to_string(i) + " is not a finite number");
        values[i] = f;
      }
      break;
  }
  return values;
}

// Exactly `expected` bytes from a gzip (or zlib) stream; a short or corrupt stream is an
// error, trailing data after the stream's end too.
std::string inflate_exact(const std::filesystem::path& path, std::string_view compressed, std::size_t expected) {
  std::string out(expected, '\0');
  z_stream z{};
  if (inflateInit2(&z, 15 + 32) != Z_OK) throw file_error(path, "cannot initialise zlib");
  z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(compressed.data()));
  z.avail_in = 0;
  std::size_t in_left = compressed.size();
  z.next_out = reinterpret_cast<Bytef*>(out.data());
  z.avail_out = 0;
  std::size_t out_left = expected;
  int status = Z_OK;
  // zlib counts in 32-bit uInt: feed both sides in chunks.
  constexpr std::size_t chunk = std::size_t(1) << 30;
  while (status == Z_OK) {
    if (z.avail_in == 0 && in_left > 0) {
      z.avail_in = uInt(std::min(in_left, chunk));
      in_left -= z.avail_in;
    }
    if (z.avail_out == 0 && out_left > 0) {
      z.avail_out = uInt(std::min(out_left, chunk));
      out_left -= z.avail_out;
    }
    if (z.avail_out == 0) {  // every expected byte is in: the stream must end here
      unsigned char probe;
      z.next_out = &probe;
      z.avail_out = 1;
      status = inflate(&z, Z_NO_FLUSH);
      if (z.avail_out == 0) {
        inflateEnd(&z);
        throw file_error(path, "gzip data holds more than the " + std::to_string(expected) + " bytes the header promises");
      }
      break;
    }
    status = inflate(&z, Z_NO_FLUSH);
    if (status == Z_BUF_ERROR && z.avail_in == 0 && in_left == 0) break;
  }
  const std::size_t produced = std::size_t(z.total_out);
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

std::string describe(ivec3 d) {
  return std::to_string(d.x) + "x" + std::to_string(d.y) + "x" + std::to_string(d.z);
}

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

}  // namespace

ivec3 parse_dims(std::string_view text) {
  const auto parts = split(text, "xX");
  ivec3 d(0);
  std::int64_t v[3];
  if (parts.size() != 3 || text.find_first_not_of("0123456789xX") != std::string_view::npos ||
      !parse_int64(parts[0], v[0]) || !parse_int64(parts[1], v[1]) || !parse_int64(parts[2], v[2]))
    throw Error("--dims '" + std::string(text) + "': expected XxYxZ, e.g. 64x64x64");
  for (int a = 0; a < 3; ++a) {
    if (v[a] <= 0) throw Error("--dims '" + std::string(text) + "': every dimension must be positive");
    if (v[a] > (std::int64_t(1) << 30)) throw Error("--dims '" + std::string(text) + "': dimension too large (overflow)");
    d[a] = int(v[a]);
  }
  checked_voxel_count(d, "--dims '" + std::string(text) + "'");
  return d;
}

vec3 parse_spacing(std::string_view text) {
  const auto parts = split(text, ",");
  vec3 s;
  if (parts.size() != 3 || !parse_float(parts[0], s.x) || !parse_float(parts[1], s.y) || !parse_float(parts[2], s.z) ||
      !(s.x > 0 && s.y > 0 && s.z > 0))
    throw Error("--spacing '" + std::string(text) + "': expected three positive numbers sx,sy,sz");
  return s;
}

VoxelType parse_voxel_type(std::string_view text) {
  if (text == "uint8") return VoxelType::uint8;
  if (text == "uint16") return VoxelType::uint16;
  if (text == "float32") return VoxelType::float32;
  throw Error("--type '" + std::string(text) + "': expected uint8, uint16 or float32");
}

Volume read_raw_volume(const std::filesystem::path& path, const RawVolumeFormat& format) {
  const std::int64_t count = checked_voxel_count(format.dims, path.string());
  const std::string bytes = read_file(path);
  const std::int64_t expected = count * type_size(format.type);
  if (std::int64_t(bytes.size()) != expected)
    throw file_error(path, "holds " + std::to_string(bytes.size()) + " bytes, but " + describe(format.dims) + " " +
                               (format.type == VoxelType::uint8    ? "uint8"
                                : format.type == VoxelType::uint16 ? "uint16"
                                                                   : "float32") +
                               " voxels need " + std::to_string(expected));
  Volume v;
  v.dims = format.dims;
  v.spacing = format.spacing;
  v.values = decode(path, bytes.data(), count, format.type, format.big_endian);
  return v;
}

Volume read_nrrd(const std::filesystem::path& path) {
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
    if (colon == std::string::npos) throw file_error(path, "malformed NRRD header line '" + line + "'");
    const std::string field = lower(trim(line.substr(0, colon)));
    const std::string value = trim(line.substr(colon + 2));
    const auto bad = [&] { return file_error(path, "unsupported NRRD " + field + " '" + value + "'"); };
    if (field == "type") {
      const std::string t = lower(value);
      if (t == "uchar" || t == "unsigned char" || t == "uint8" || t == "uint8_t") type = VoxelType::uint8;
      else if (t == "ushort" || t == "unsigned short" || t == "unsigned short int" || t == "uint16" || t == "uint16_t")
        type = VoxelType::uint16;
      else if (t == "float") type = VoxelType::float32;
      else throw bad();
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
          throw file_error(path, "NRRD sizes '" + value + "': every size must be positive and not overflow");
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
          if (b != a && d[b] != 0) throw file_error(path, "unsupported NRRD space directions '" + value + "' (only diagonal)");
        if (!(d[a] > 0)) throw file_error(path, "unsupported NRRD space directions '" + value + "' (only positive diagonal)");
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
      throw file_error(path, "unsupported NRRD field '" + field + "'");
    }
  }
  if (!type) throw file_error(path, "NRRD header has no type");
  if (dimension != 3) throw file_error(path, "NRRD header has no 'dimension: 3'");
  if (!have_sizes) throw file_error(path, "NRRD header has no sizes");
  if (byte_skip == -1 && gzip) throw file_error(path, "unsupported NRRD byte skip -1 with gzip encoding");

  const std::int64_t count = std::int64_t(dims.x) * dims.y * dims.z;
  const std::size_t expected = std::size_t(count) * std::size_t(type_size(*type));
  std::string detached;
  std::filesystem::path data_path = path;
  std::string_view data;
  if (attached) {
    data = std::string_view(file).substr(std::min(pos, file.size()));
  } else {
    data_path = std::filesystem::path(data_file).is_absolute() ? std::filesystem::path(data_file)
                                                               : path.parent_path() / data_file;
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
  Volume v;
  v.dims = dims;
  v.spacing = spacing;
  v.origin = origin;
  v.values = decode(data_path, data.data(), count, *type, big_endian);
  return v;
}

Volume read_volume(const std::filesystem::path& path, const std::optional<RawVolumeFormat>& raw) {
  const std::string ext = lower(path.extension().string());
  if (ext == ".nrrd" || ext == ".nhdr") {
    if (raw) throw Error(path.string() + ": a NRRD header describes the volume; drop --dims/--type/--spacing/--endian");
    return read_nrrd(path);
  }
  if (!raw) throw Error(path.string() + ": a raw volume needs --dims XxYxZ (and --type unless uint8)");
  return read_raw_volume(path, *raw);
}

}  // namespace pss
