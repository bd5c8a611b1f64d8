// NIfTI-1 single files (.nii, .nii.gz) through the reference library (niftiio, Debian's
// libnifti2-dev). The library reports problems on stderr and carries on with what it
// guessed, so pss checks the header first itself: magic, byte order, dims, type, spacing,
// and that the file holds every voxel the header promises, and reads the voxels then, as
// the other formats do (decode: either byte order; a value that is not a finite float is
// an error, where the library would turn it into 0 without a word). The library reads the
// header's geometry and value scaling; a failure there is still our one line.
//
// Geometry: spacing is |pixdim[1..3]|. The origin is the translation of the sform when its
// code is set, else of the qform, else 0; their rotation and any flips are not applied (pss
// grids are axis-aligned, i along x), so the volume is drawn in voxel-axis orientation.
#include <zlib.h>

#include <algorithm>
#include <bit>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <optional>
#include <vector>
#include <memory>
#include <string>

#include <nifti1_io.h>

#include "pss/core/error.hpp"
#include "pss/io/volume_file.hpp"
#include "bytes.hpp"
#include "volume_decode.hpp"

namespace pss::volume_io {

namespace {

std::optional<VoxelType> nifti_type(int datatype) {
  switch (datatype) {
    case DT_INT8: return VoxelType::int8;
    case DT_UINT8: return VoxelType::uint8;
    case DT_INT16: return VoxelType::int16;
    case DT_UINT16: return VoxelType::uint16;
    case DT_INT32: return VoxelType::int32;
    case DT_UINT32: return VoxelType::uint32;
    case DT_FLOAT32: return VoxelType::float32;
    case DT_FLOAT64: return VoxelType::float64;
    default: return std::nullopt;
  }
}

struct GzCloser {
  void operator()(gzFile_s* g) const { gzclose(g); }
};
struct NiftiFree {
  void operator()(nifti_image* n) const { nifti_image_free(n); }
};

// Reads up to n bytes; -1 on a corrupt stream.
std::int64_t read_some(gzFile g, char* into, std::int64_t n) {
  std::int64_t got = 0;
  while (got < n) {
    const int chunk = int(std::min<std::int64_t>(n - got, std::int64_t(1) << 30));
    const int r = gzread(g, into + got, unsigned(chunk));
    if (r < 0) return -1;
    if (r == 0) break;
    got += r;
  }
  return got;
}

// Reads and drops up to n bytes; returns how many there were.
std::int64_t skip_bytes(const std::filesystem::path& path, gzFile g, std::int64_t n) {
  constexpr std::int64_t kPiece = std::int64_t(1) << 20;
  std::vector<char> buffer(std::size_t(std::min(std::max<std::int64_t>(n, 0), kPiece)));
  std::int64_t done = 0;
  while (done < n) {
    const std::int64_t r = read_some(g, buffer.data(), std::min(n - done, kPiece));
    if (r < 0) throw file_error(path, "corrupt gzip data");
    if (r == 0) break;
    done += r;
  }
  return done;
}

// The header fields pss needs, validated, in the machine's byte order, and the voxels'
// bytes as the file holds them.
struct CheckedHeader {
  ivec3 dims;
  VoxelType type;
  bool big_endian;
  bool compressed;
  std::int64_t vox_offset;
  std::string voxels;
};

std::string number(double x) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%g", x);
  return buffer;
}

CheckedHeader read_checked(const std::filesystem::path& path) {
  std::unique_ptr<gzFile_s, GzCloser> g(gzopen(path.c_str(), "rb"));
  if (!g) throw file_error(path, std::string("cannot open: ") + std::strerror(errno));
  nifti_1_header h;
  static_assert(sizeof(nifti_1_header) == 348);
  const std::int64_t got = read_some(g.get(), reinterpret_cast<char*>(&h), 348);
  if (got < 0) throw file_error(path, "corrupt gzip data");
  if (got < 348) throw file_error(path, "holds " + std::to_string(got) + " bytes, too few for a NIfTI-1 header (348)");
  const bool compressed = !gzdirect(g.get());
  const std::string name = lower(path.filename().string());
  if (compressed != (name.size() > 3 && name.compare(name.size() - 3, 3, ".gz") == 0))
    throw file_error(path, compressed ? "is gzip-compressed: name it .nii.gz" : "is not gzip-compressed: name it .nii");

  // The byte order: sizeof_hdr is 348 in the writer's order.
  bool swap = false;
  if (h.sizeof_hdr != 348) {
    swap = io::load<std::int32_t>(reinterpret_cast<const char*>(&h.sizeof_hdr), true) == 348;
    if (!swap) {
      const bool nifti2 =
          h.sizeof_hdr == 540 || io::load<std::int32_t>(reinterpret_cast<const char*>(&h.sizeof_hdr), true) == 540;
      throw file_error(path, nifti2 ? "is NIfTI-2; pss reads NIfTI-1" : "not a NIfTI-1 file (sizeof_hdr is not 348)");
    }
  }
  const auto i16 = [&](const short& v) { return io::load<std::int16_t>(reinterpret_cast<const char*>(&v), swap); };
  const auto f32 = [&](const float& v) { return io::load<float>(reinterpret_cast<const char*>(&v), swap); };
  if (std::memcmp(h.magic, "ni1", 4) == 0)
    throw file_error(path, "is the header of a .hdr/.img pair; pss reads single-file NIfTI (.nii, magic n+1)");
  if (std::memcmp(h.magic, "n+1", 4) != 0) throw file_error(path, "not a NIfTI-1 file (no n+1 magic)");

  const int ndim = i16(h.dim[0]);
  if (ndim < 3 || ndim > 4)
    throw file_error(path, "NIfTI dim[0] = " + std::to_string(ndim) + ": pss reads 3-D volumes only");
  CheckedHeader c;
  for (int a = 0; a < 3; ++a) {
    const int n = i16(h.dim[a + 1]);
    if (n <= 0)
      throw file_error(path, "NIfTI dim[" + std::to_string(a + 1) + "] = " + std::to_string(n) + " is not positive");
    c.dims[a] = n;
  }
  if (ndim == 4 && i16(h.dim[4]) != 1)
    throw file_error(path, "NIfTI dim[4] = " + std::to_string(i16(h.dim[4])) + ": pss reads one volume, not a series");
  const int datatype = i16(h.datatype);
  const std::optional<VoxelType> type = nifti_type(datatype);
  if (!type)
    throw file_error(path, "NIfTI datatype " + std::to_string(datatype) +
                               " is not supported (int8/16/32, uint8/16/32, float32/64 only)");
  c.type = *type;
  if (i16(h.bitpix) != 8 * voxel_type_size(*type))
    throw file_error(path, "NIfTI bitpix " + std::to_string(i16(h.bitpix)) + " does not match datatype " +
                               voxel_type_name(*type));
  for (int a = 1; a <= 3; ++a) {
    const float s = std::abs(f32(h.pixdim[a]));
    if (!std::isfinite(s) || !(s > 0))
      throw file_error(path, "NIfTI pixdim[" + std::to_string(a) + "] = " + number(f32(h.pixdim[a])) +
                                 " is not a positive spacing");
  }
  const float offset = f32(h.vox_offset);
  if (!std::isfinite(offset) || offset < 352 || offset > float(std::int64_t(1) << 40) || offset != std::floor(offset))
    throw file_error(path, "NIfTI vox_offset " + number(offset) + " is not a byte offset >= 352");
  c.vox_offset = std::int64_t(offset);
  c.big_endian = swap != (std::endian::native == std::endian::big);
  c.compressed = compressed;

  // Every voxel must be there before memory is taken for them: an uncompressed file's size
  // says so; a compressed one is read through once, then again into a buffer of the size it
  // proved to hold (as much as the header claims, but no more than the file holds).
  const std::int64_t count = checked_voxel_count(c.dims, path.string());
  const std::int64_t voxel_bytes = count * voxel_type_size(*type);
  const std::int64_t needed = c.vox_offset + voxel_bytes;
  const auto too_short = [&](std::int64_t have) {
    return file_error(path, "holds " + std::to_string(have) + (compressed ? " uncompressed" : "") +
                                " bytes, but vox_offset " + std::to_string(c.vox_offset) + " + " + describe(c.dims) +
                                " " + voxel_type_name(*type) + " voxels need " + std::to_string(needed));
  };
  std::int64_t position = 348;
  if (!compressed) {
    std::error_code ec;
    const std::int64_t size = std::int64_t(std::filesystem::file_size(path, ec));
    if (ec) throw file_error(path, "cannot read: " + ec.message());
    if (size < needed) throw too_short(size);
  } else {
    const std::int64_t have = position + skip_bytes(path, g.get(), needed - position);
    if (have < needed) throw too_short(have);
    if (gzrewind(g.get()) != 0) throw file_error(path, "cannot read: gzrewind failed");
    position = 0;
  }
  // The extensions, between the header and vox_offset, are the library's business.
  position += skip_bytes(path, g.get(), c.vox_offset - position);
  if (position != c.vox_offset) throw too_short(position);  // shorter than a moment ago
  c.voxels.resize(std::size_t(voxel_bytes));
  const std::int64_t read = read_some(g.get(), c.voxels.data(), voxel_bytes);
  if (read < 0) throw file_error(path, "corrupt gzip data");
  if (read < voxel_bytes) throw too_short(c.vox_offset + read);  // shorter than a moment ago
  return c;
}

}  // namespace

VolumeFile read_nifti_file(const std::filesystem::path& path) {
  const CheckedHeader header = read_checked(path);
  nifti_set_debug_level(0);  // problems are reported by us, in one line
  std::unique_ptr<nifti_image, NiftiFree> nim(nifti_image_read(path.c_str(), 0));  // the header only
  if (!nim) throw file_error(path, "the NIfTI library could not read the header");
  if (nim->nx != header.dims.x || nim->ny != header.dims.y || nim->nz != header.dims.z ||
      nim->nvox != std::size_t(header.dims.x) * header.dims.y * header.dims.z ||
      nifti_type(nim->datatype) != header.type)
    throw file_error(path, "the NIfTI library read a different header than pss checked");

  VolumeFile f;
  Volume& v = f.volume;
  v.dims = header.dims;
  v.spacing = vec3(std::abs(nim->dx), std::abs(nim->dy), std::abs(nim->dz));
  const mat44* m = nim->sform_code > 0 ? &nim->sto_xyz : nim->qform_code > 0 ? &nim->qto_xyz : nullptr;
  if (m) v.origin = vec3(m->m[0][3], m->m[1][3], m->m[2][3]);
  if (!(std::isfinite(v.origin.x) && std::isfinite(v.origin.y) && std::isfinite(v.origin.z))) v.origin = vec3(0.0f);
  v.values = decode(path, header.voxels.data(), v.voxel_count(), header.type, header.big_endian);
  f.source = {"NIfTI-1", header.type, header.big_endian, header.compressed, {}};
  // NIfTI §scl_slope: stored values become slope·x + inter when slope is not 0 (the library
  // turns a non-finite slope or intercept into 0).
  const float slope = nim->scl_slope, inter = nim->scl_inter;
  if (slope != 0 && !(slope == 1 && inter == 0)) {
    for (std::size_t i = 0; i < v.values.size(); ++i) {
      v.values[i] = slope * v.values[i] + inter;
      if (!std::isfinite(v.values[i]))
        throw file_error(path, "voxel " + std::to_string(i) + " is not a finite number after scl_slope/scl_inter");
    }
    f.source.note = "scaled by scl_slope " + number(slope) + ", scl_inter " + number(inter);
  }
  return f;
}

}  // namespace pss::volume_io

namespace pss {

Volume read_nifti(const std::filesystem::path& path) { return volume_io::read_nifti_file(path).volume; }

}  // namespace pss
