// The volume formats CT and MRI data come in, each written here by hand (not by the reader's
// library) so that the tests check the readers against the formats' definitions: every voxel
// type in both byte orders for raw (with --skip) and NRRD (with every spelling of `type:`),
// MetaImage .mhd/.mha plain and zlib-compressed, NIfTI-1 .nii/.nii.gz from a hand-filled
// 348-byte header; then lying and truncated headers, each a one-line error naming the file.
#include <gtest/gtest.h>
#include <zlib.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include <unistd.h>

#include "pss/core/error.hpp"
#include "pss/io/volume_file.hpp"
#include "support/cli.hpp"

namespace pss {
namespace {

namespace fs = std::filesystem;

class VolumeFormats : public testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("pss-volume-formats-" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path write(const std::string& name, const std::string& bytes) const {
    std::ofstream(dir_ / name, std::ios::binary) << bytes;
    return dir_ / name;
  }
  fs::path dir_;
};

const ivec3 kDims(2, 3, 4);
constexpr int kCount = 24;

const VoxelType kTypes[] = {VoxelType::int8,  VoxelType::uint8,  VoxelType::int16,   VoxelType::uint16,
                            VoxelType::int32, VoxelType::uint32, VoxelType::float32, VoxelType::float64};

// Voxel i of a test volume of `type`: values that use the type's range (negative ones for
// the signed types, beyond 16 bits for the 32-bit ones, fractions for the floats).
double value_of(VoxelType type, int i) {
  switch (type) {
    case VoxelType::int8: return -100 + 7 * i;
    case VoxelType::uint8: return 200 + i;
    case VoxelType::int16: return -30000 + 2500 * i;
    case VoxelType::uint16: return 60000 + 200 * i;
    case VoxelType::int32: return -2000000000.0 + 100000007.0 * i;
    case VoxelType::uint32: return 3000000000.0 + 12345.0 * i;
    case VoxelType::float32: return -1.5 * i + 0.25;
    case VoxelType::float64: return 1.0e10 + 0.5 * i;
  }
  return 0;
}

template <class T>
std::string bytes_of(T x, bool big_endian) {
  std::string s(sizeof(T), '\0');
  std::memcpy(s.data(), &x, sizeof(T));
  if (big_endian != (std::endian::native == std::endian::big)) std::reverse(s.begin(), s.end());
  return s;
}

std::string encode(VoxelType type, double v, bool big) {
  switch (type) {
    case VoxelType::int8: return bytes_of(std::int8_t(v), big);
    case VoxelType::uint8: return bytes_of(std::uint8_t(v), big);
    case VoxelType::int16: return bytes_of(std::int16_t(v), big);
    case VoxelType::uint16: return bytes_of(std::uint16_t(v), big);
    case VoxelType::int32: return bytes_of(std::int32_t(v), big);
    case VoxelType::uint32: return bytes_of(std::uint32_t(v), big);
    case VoxelType::float32: return bytes_of(float(v), big);
    case VoxelType::float64: return bytes_of(double(v), big);
  }
  return {};
}

std::string voxels(VoxelType type, bool big) {
  std::string s;
  for (int i = 0; i < kCount; ++i) s += encode(type, value_of(type, i), big);
  return s;
}

// What the reader must return: the value converted to float as C++ does (int32, uint32 and
// float64 round to float's 24-bit mantissa).
void expect_values(const Volume& v, VoxelType type, const std::string& what) {
  ASSERT_EQ(v.dims, kDims) << what;
  ASSERT_EQ(v.values.size(), std::size_t(kCount)) << what;
  for (int i = 0; i < kCount; ++i) EXPECT_EQ(v.values[i], float(value_of(type, i))) << what << " voxel " << i;
}

std::string zlib_compress(const std::string& data) {
  uLongf size = compressBound(uLong(data.size()));
  std::string out(size, '\0');
  compress2(reinterpret_cast<Bytef*>(out.data()), &size, reinterpret_cast<const Bytef*>(data.data()),
            uLong(data.size()), 9);
  out.resize(size);
  return out;
}

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

// The error contract: one line, naming the file, saying `what`.
void expect_error(const std::function<void()>& f, const fs::path& file, const std::string& what) {
  const std::string m = error_of(f);
  EXPECT_EQ(m.find('\n'), std::string::npos) << m;
  EXPECT_NE(m.find(file.filename().string()), std::string::npos) << m;
  EXPECT_NE(m.find(what), std::string::npos) << "expected '" << what << "' in: " << m;
}

TEST_F(VolumeFormats, RawEveryTypeBothByteOrdersAndSkip) {
  for (VoxelType type : kTypes)
    for (bool big : {false, true}) {
      const std::string what = std::string(voxel_type_name(type)) + (big ? " big" : " little");
      RawVolumeFormat f;
      f.dims = kDims;
      f.type = parse_voxel_type(voxel_type_name(type));
      f.big_endian = big;
      expect_values(read_volume(write("v.raw", voxels(type, big)), f), type, what);
      // --skip: a 37-byte header of anything, then the voxels.
      f.skip = parse_skip("37");
      expect_values(read_volume(write("v.dat", std::string(37, 'H') + voxels(type, big)), f), type, what + " skip");
      // skip + voxels must be the whole file: one byte more or less is a lie.
      expect_error([&] { read_volume(write("long.dat", std::string(38, 'H') + voxels(type, big)), f); },
                   dir_ / "long.dat", "37 skipped");
      expect_error([&] { read_volume(write("short.dat", std::string(36, 'H') + voxels(type, big)), f); },
                   dir_ / "short.dat", "holds");
    }
  EXPECT_NE(error_of([] { parse_voxel_type("int64"); }).find("expected int8, uint8"), std::string::npos);
  EXPECT_NE(error_of([] { parse_skip("-4"); }).find("--skip"), std::string::npos);
  EXPECT_NE(error_of([] { parse_skip("12abc"); }).find("--skip"), std::string::npos);
}

TEST_F(VolumeFormats, NrrdEveryTypeSpellingBothByteOrders) {
  const std::vector<std::pair<VoxelType, std::vector<std::string>>> spellings = {
      {VoxelType::int8, {"signed char", "int8", "int8_t"}},
      {VoxelType::uint8, {"uchar", "unsigned char", "uint8", "uint8_t"}},
      {VoxelType::int16, {"short", "short int", "signed short", "signed short int", "int16", "int16_t"}},
      {VoxelType::uint16, {"ushort", "unsigned short", "unsigned short int", "uint16", "uint16_t"}},
      {VoxelType::int32, {"int", "signed int", "int32", "int32_t"}},
      {VoxelType::uint32, {"uint", "unsigned int", "uint32", "uint32_t"}},
      {VoxelType::float32, {"float"}},
      {VoxelType::float64, {"double"}},
  };
  for (const auto& [type, names] : spellings)
    for (const std::string& name : names)
      for (bool big : {false, true}) {
        const std::string header = "NRRD0004\ntype: " + name + "\ndimension: 3\nsizes: 2 3 4\nspacings: 0.5 1 2\n" +
                                   "endian: " + (big ? "big" : "little") + "\nencoding: raw\n\n";
        const Volume v = read_volume(write("v.nrrd", header + voxels(type, big)), std::nullopt);
        expect_values(v, type, name + (big ? " big" : " little"));
        EXPECT_EQ(v.spacing, vec3(0.5f, 1.0f, 2.0f));
        const VolumeFile f = read_volume_file(dir_ / "v.nrrd", std::nullopt);
        EXPECT_EQ(f.source.type, type);
        EXPECT_EQ(f.source.format, "NRRD");
      }
  expect_error([&] { read_volume(write("t.nrrd", "NRRD0004\ntype: int64\ndimension: 3\nsizes: 2 3 4\n\n"), std::nullopt); },
               dir_ / "t.nrrd", "unsupported NRRD type 'int64'");
  expect_error([&] { read_volume(write("t.nrrd", "NRRD0004\ntype: shorts\ndimension: 3\nsizes: 2 3 4\n\n"), std::nullopt); },
               dir_ / "t.nrrd", "unsupported NRRD type");
  // A double beyond float's range is not a finite float.
  expect_error([&] {
    read_volume(write("big.nrrd", "NRRD0004\ntype: double\ndimension: 3\nsizes: 1 1 1\nencoding: raw\n\n" +
                                      bytes_of(1e300, false)),
                std::nullopt);
  }, dir_ / "big.nrrd", "not a finite number as a float");
}

TEST_F(VolumeFormats, MetaImageDetachedLocalAndCompressed) {
  const std::pair<VoxelType, const char*> met[] = {
      {VoxelType::int8, "MET_CHAR"},  {VoxelType::uint8, "MET_UCHAR"}, {VoxelType::int16, "MET_SHORT"},
      {VoxelType::uint16, "MET_USHORT"}, {VoxelType::int32, "MET_INT"}, {VoxelType::uint32, "MET_UINT"},
      {VoxelType::float32, "MET_FLOAT"}, {VoxelType::float64, "MET_DOUBLE"}};
  for (const auto& [type, name] : met)
    for (bool big : {false, true}) {
      const std::string what = std::string(name) + (big ? " MSB" : " LSB");
      const std::string common = std::string("ObjectType = Image\nNDims = 3\nDimSize = 2 3 4\nElementType = ") + name +
                                 "\nElementSpacing = 0.5 0.25 2\nOffset = 10 -20 30.5\n" +
                                 "BinaryData = True\nBinaryDataByteOrderMSB = " + (big ? "True" : "False") + "\n";
      write("v.raw", voxels(type, big));
      const Volume d = read_volume(write("v.mhd", common + "ElementDataFile = v.raw\n"), std::nullopt);
      expect_values(d, type, what + " .mhd");
      EXPECT_EQ(d.spacing, vec3(0.5f, 0.25f, 2.0f));
      EXPECT_EQ(d.origin, vec3(10.0f, -20.0f, 30.5f));
      expect_values(read_volume(write("v.mha", common + "ElementDataFile = LOCAL\n" + voxels(type, big)), std::nullopt),
                    type, what + " .mha");
      const std::string z = zlib_compress(voxels(type, big));
      const VolumeFile c = read_volume_file(
          write("c.MHA", common + "CompressedData = True\nCompressedDataSize = " + std::to_string(z.size()) +
                             "\nElementDataFile = LOCAL\n" + z),
          std::nullopt);
      expect_values(c.volume, type, what + " compressed .mha");
      EXPECT_TRUE(c.source.compressed);
      EXPECT_EQ(c.source.type, type);
      write("c.zraw", z);
      expect_values(read_volume(write("c.mhd", common + "CompressedData = True\nElementDataFile = c.zraw\n"),
                                std::nullopt),
                    type, what + " compressed .mhd");
    }
  // In a subfolder, with a header to skip, ElementSize for the spacing, an identity matrix
  // and CRLF line ends.
  fs::create_directories(dir_ / "sub");
  write("sub/d.img", "0123456789" + voxels(VoxelType::uint8, false));
  const std::string h = "NDims = 3\r\nDimSize = 2 3 4\r\nElementType = MET_UCHAR\r\nElementSize = 1 2 3\r\n"
                        "TransformMatrix = 1 0 0 0 1 0 0 0 1\r\nAnatomicalOrientation = RAI\r\n";
  const Volume s = read_volume(write("sub/d.mhd", h + "HeaderSize = 10\r\nElementDataFile = d.img\r\n"), std::nullopt);
  expect_values(s, VoxelType::uint8, "HeaderSize 10");
  EXPECT_EQ(s.spacing, vec3(1.0f, 2.0f, 3.0f));
  expect_values(read_volume(write("sub/e.mhd", h + "HeaderSize = -1\r\nElementDataFile = d.img\r\n"), std::nullopt),
                VoxelType::uint8, "HeaderSize -1");
}

TEST_F(VolumeFormats, MetaImageLiesAreOneLineErrors) {
  const std::string body = voxels(VoxelType::uint8, false);
  const std::string ok = "NDims = 3\nDimSize = 2 3 4\nElementType = MET_UCHAR\n";
  const auto mha = [&](const std::string& name, const std::string& header, const std::string& data) {
    const fs::path p = write(name, header + "ElementDataFile = LOCAL\n" + data);
    return [p] { read_volume(p, std::nullopt); };
  };
  expect_error(mha("a.mha", "NDims = 2\nDimSize = 2 3\nElementType = MET_UCHAR\n", body), dir_ / "a.mha",
               "3-D volumes only");
  expect_error(mha("b.mha", "NDims = 3\nDimSize = 2 3 5\nElementType = MET_UCHAR\n", body), dir_ / "b.mha",
               "need 30");
  expect_error(mha("c.mha", "NDims = 3\nDimSize = 2 3 4\nElementType = MET_LONG_LONG\n", body), dir_ / "c.mha",
               "MET_LONG_LONG");
  expect_error(mha("d.mha", ok + "ElementSpacing = 1 0 1\n", body), dir_ / "d.mha", "positive");
  expect_error(mha("e.mha", ok + "ElementSpacing = 1 1\n", body), dir_ / "e.mha", "three numbers");
  expect_error(mha("f.mha", ok + "HeaderSize = 100\n", body), dir_ / "f.mha", "beyond");
  expect_error(mha("g.mha", ok + "ElementNumberOfChannels = 3\n", body), dir_ / "g.mha", "1 channel");
  expect_error(mha("h.mha", ok + "TransformMatrix = 0 1 0 1 0 0 0 0 1\n", body), dir_ / "h.mha", "identity");
  expect_error(mha("i.mha", ok + "CompressedData = True\n", zlib_compress(body).substr(0, 10)), dir_ / "i.mha",
               "gzip");
  expect_error(mha("j.mha", ok + "CompressedData = True\n", zlib_compress(body + "x")), dir_ / "j.mha", "more than");
  expect_error(mha("k.mha", "NDims = 3\nElementType = MET_UCHAR\n", body), dir_ / "k.mha", "no DimSize");
  expect_error(mha("l.mha", ok + "BinaryData = False\n", body), dir_ / "l.mha", "ASCII");
  expect_error(mha("m.mha", ok, body + "extra"), dir_ / "m.mha", "holds 29 bytes");
  expect_error([&] { read_volume(write("n.mhd", ok + "ElementDataFile = missing.raw\n"), std::nullopt); },
               dir_ / "missing.raw", "cannot open");
  expect_error([&] { read_volume(write("o.mha", "just some text"), std::nullopt); }, dir_ / "o.mha", "no '='");
  expect_error([&] { read_volume(write("p.mhd", ok), std::nullopt); }, dir_ / "p.mhd", "no ElementDataFile");
}

// NIfTI-1's header as the standard lays it out (nifti1.h), filled by hand: 348 bytes, every
// field at its natural alignment, so no packing is needed.
struct Nifti1Header {
  std::int32_t sizeof_hdr = 348;
  char data_type[10] = {};
  char db_name[18] = {};
  std::int32_t extents = 0;
  std::int16_t session_error = 0;
  char regular = 'r';
  char dim_info = 0;
  std::int16_t dim[8] = {3, 2, 3, 4, 1, 1, 1, 1};
  float intent_p1 = 0, intent_p2 = 0, intent_p3 = 0;
  std::int16_t intent_code = 0, datatype = 0, bitpix = 0, slice_start = 0;
  float pixdim[8] = {1, 0.5f, -0.75f, 2, 1, 1, 1, 1};  // qfac, then spacings (a negative one: flipped axis)
  float vox_offset = 352;
  float scl_slope = 0, scl_inter = 0;
  std::int16_t slice_end = 0;
  char slice_code = 0, xyzt_units = 2;
  float cal_max = 0, cal_min = 0, slice_duration = 0, toffset = 0;
  std::int32_t glmax = 0, glmin = 0;
  char descrip[80] = {};
  char aux_file[24] = {};
  std::int16_t qform_code = 0, sform_code = 1;
  float quatern_b = 0, quatern_c = 0, quatern_d = 0, qoffset_x = 0, qoffset_y = 0, qoffset_z = 0;
  float srow_x[4] = {0.5f, 0, 0, -12.5f}, srow_y[4] = {0, 0.75f, 0, 7}, srow_z[4] = {0, 0, 2, 3.25f};
  char intent_name[16] = {};
  char magic[4] = {'n', '+', '1', '\0'};
};
static_assert(sizeof(Nifti1Header) == 348);

int nifti_datatype(VoxelType t) {
  switch (t) {
    case VoxelType::int8: return 256;
    case VoxelType::uint8: return 2;
    case VoxelType::int16: return 4;
    case VoxelType::uint16: return 512;
    case VoxelType::int32: return 8;
    case VoxelType::uint32: return 768;
    case VoxelType::float32: return 16;
    case VoxelType::float64: return 64;
  }
  return 0;
}

// The header's bytes in the given byte order.
std::string header_bytes(const Nifti1Header& h, bool big) {
  std::string s(348, '\0');
  std::memcpy(s.data(), &h, 348);
  if (big == (std::endian::native == std::endian::big)) return s;
  const auto flip = [&](std::size_t offset, std::size_t size, int count) {
    for (int i = 0; i < count; ++i) std::reverse(s.begin() + offset + i * size, s.begin() + offset + (i + 1) * size);
  };
  flip(0, 4, 1);                                        // sizeof_hdr
  flip(32, 4, 1);                                       // extents
  flip(36, 2, 1);                                       // session_error
  flip(40, 2, 8);                                       // dim
  flip(56, 4, 3);                                       // intent_p1..3
  flip(68, 2, 4);                                       // intent_code, datatype, bitpix, slice_start
  flip(76, 4, 8 + 1 + 2);                               // pixdim, vox_offset, scl_slope, scl_inter
  flip(120, 2, 1);                                      // slice_end
  flip(124, 4, 4 + 2);                                  // cal_max .. toffset, glmax, glmin
  flip(252, 2, 2);                                      // qform_code, sform_code
  flip(256, 4, 6 + 12);                                 // quaternion, offsets, srow_x/y/z
  return s;
}

std::string nifti_file(const Nifti1Header& h, const std::string& data, bool big) {
  return header_bytes(h, big) + std::string(4, '\0') + data;  // no extensions
}

void write_gz(const fs::path& p, const std::string& bytes) {
  gzFile g = gzopen(p.c_str(), "wb");
  gzwrite(g, bytes.data(), unsigned(bytes.size()));
  gzclose(g);
}

TEST_F(VolumeFormats, NiftiEveryTypePlainAndGzip) {
  for (VoxelType type : kTypes)
    for (bool big : {false, true}) {
      const std::string what = std::string(voxel_type_name(type)) + (big ? " big" : " little");
      Nifti1Header h;
      h.datatype = std::int16_t(nifti_datatype(type));
      h.bitpix = std::int16_t(8 * voxel_type_size(type));
      const std::string file = nifti_file(h, voxels(type, big), big);
      const VolumeFile f = read_volume_file(write("v.nii", file), std::nullopt);
      expect_values(f.volume, type, what + " .nii");
      EXPECT_EQ(f.volume.spacing, vec3(0.5f, 0.75f, 2.0f)) << what;
      EXPECT_EQ(f.volume.origin, vec3(-12.5f, 7.0f, 3.25f)) << what;  // the sform's translation
      EXPECT_EQ(f.source.type, type);
      EXPECT_EQ(f.source.big_endian, big);
      write_gz(dir_ / "v.nii.gz", file);
      const VolumeFile g = read_volume_file(dir_ / "v.nii.gz", std::nullopt);
      expect_values(g.volume, type, what + " .nii.gz");
      EXPECT_TRUE(g.source.compressed);
    }
  // dim[0] = 4 with one volume; scl_slope/scl_inter applied; the qform's offset when there is
  // no sform.
  Nifti1Header h;
  h.dim[0] = 4;
  h.datatype = 4;
  h.bitpix = 16;
  h.scl_slope = 2;
  h.scl_inter = -1;
  h.sform_code = 0;
  h.qform_code = 1;
  h.qoffset_x = 1;
  h.qoffset_y = 2;
  h.qoffset_z = 3;
  const Volume v = read_volume(write("s.nii", nifti_file(h, voxels(VoxelType::int16, false), false)), std::nullopt);
  ASSERT_EQ(v.values.size(), std::size_t(kCount));
  for (int i = 0; i < kCount; ++i) EXPECT_EQ(v.values[i], 2.0f * float(value_of(VoxelType::int16, i)) - 1.0f);
  EXPECT_EQ(v.origin, vec3(1.0f, 2.0f, 3.0f));
}

TEST_F(VolumeFormats, NiftiLiesAreOneLineErrors) {
  const std::string data = voxels(VoxelType::uint8, false);
  Nifti1Header good;
  good.datatype = 2;
  good.bitpix = 8;
  const auto check = [&](const std::string& name, const std::function<void(Nifti1Header&)>& lie,
                         const std::string& what, const std::string& body) {
    Nifti1Header h = good;
    lie(h);
    const fs::path p = write(name, nifti_file(h, body, false));
    expect_error([&] { read_volume(p, std::nullopt); }, p, what);
  };
  check("a.nii", [](Nifti1Header& h) { h.dim[0] = 2; }, "3-D volumes only", data);
  check("b.nii", [](Nifti1Header& h) { h.dim[0] = 5; }, "3-D volumes only", data);
  check("c.nii", [](Nifti1Header& h) { h.dim[0] = 4, h.dim[4] = 2; }, "one volume", data + data);
  check("d.nii", [](Nifti1Header& h) { h.dim[3] = 40; }, "voxels need", data);
  check("e.nii", [](Nifti1Header& h) { h.datatype = 128, h.bitpix = 24; }, "datatype 128", data);
  check("f.nii", [](Nifti1Header& h) { h.bitpix = 16; }, "bitpix", data);
  check("g.nii", [](Nifti1Header& h) { h.pixdim[2] = 0; }, "pixdim[2]", data);
  check("h.nii", [](Nifti1Header& h) { h.pixdim[1] = NAN; }, "pixdim[1]", data);
  check("i.nii", [](Nifti1Header& h) { h.vox_offset = 100; }, "vox_offset", data);
  check("j.nii", [](Nifti1Header& h) { h.vox_offset = 1e9f; }, "voxels need", data);
  check("k.nii", [](Nifti1Header& h) { h.magic[1] = 'i'; }, "n+1", data);
  check("l.nii", [](Nifti1Header& h) { h.sizeof_hdr = 349; }, "sizeof_hdr", data);
  check("m.nii", [](Nifti1Header& h) { h.dim[1] = -2; }, "dim[1]", data);
  check("n.nii", [](Nifti1Header& h) { h.datatype = 16, h.bitpix = 32, h.scl_slope = 1e30f; }, "scl_slope",
        std::string(kCount, '\x7f') + std::string(3 * kCount, '\x7f'));
  expect_error([&] { read_volume(write("o.nii", "short"), std::nullopt); }, dir_ / "o.nii", "too few");
  // gzip: truncated stream, and a compressed file named .nii.
  std::string gz;
  {
    write_gz(dir_ / "t.nii.gz", nifti_file(good, data, false));
    std::ifstream in(dir_ / "t.nii.gz", std::ios::binary);
    gz.assign(std::istreambuf_iterator<char>(in), {});
  }
  expect_error([&] { read_volume(write("u.nii.gz", gz.substr(0, gz.size() - 20)), std::nullopt); }, dir_ / "u.nii.gz",
               "");
  expect_error([&] { read_volume(write("w.nii", gz), std::nullopt); }, dir_ / "w.nii", "name it .nii.gz");
  expect_error([&] { read_volume(dir_ / "nothere.nii", std::nullopt); }, dir_ / "nothere.nii", "cannot open");
}

// The NIfTI library turns non-finite float voxels into 0 as it reads them; pss reads the
// voxels itself, so that a NaN or infinity is refused as in every other format (found by
// fuzz/corpus/nifti/float-nan).
TEST_F(VolumeFormats, NiftiNonFiniteVoxelIsAnError) {
  for (const VoxelType type : {VoxelType::float32, VoxelType::float64})
    for (const float bad : {NAN, INFINITY}) {
      Nifti1Header h;
      h.datatype = std::int16_t(nifti_datatype(type));
      h.bitpix = std::int16_t(8 * voxel_type_size(type));
      std::string data = voxels(type, false);
      if (type == VoxelType::float32) std::memcpy(data.data() + 4 * 5, &bad, 4);
      else {
        const double d = bad;
        std::memcpy(data.data() + 8 * 5, &d, 8);
      }
      const std::string file = nifti_file(h, data, false);
      expect_error([&] { read_volume(write("n.nii", file), std::nullopt); }, dir_ / "n.nii",
                   "voxel 5 is not a finite number");
      write_gz(dir_ / "n.nii.gz", file);
      expect_error([&] { read_volume(dir_ / "n.nii.gz", std::nullopt); }, dir_ / "n.nii.gz",
                   "voxel 5 is not a finite number");
    }
}

TEST_F(VolumeFormats, DispatchOnExtension) {
  EXPECT_TRUE(has_volume_header("a/B.NII.GZ"));
  EXPECT_TRUE(has_volume_header("x.Mhd"));
  EXPECT_TRUE(has_volume_header("x.nhdr"));
  EXPECT_FALSE(has_volume_header("x.gz"));
  EXPECT_FALSE(has_volume_header("x.raw"));
  RawVolumeFormat f;
  f.dims = kDims;
  write("v.mha", "NDims = 3\nDimSize = 2 3 4\nElementType = MET_UCHAR\nElementDataFile = LOCAL\n" +
                     voxels(VoxelType::uint8, false));
  expect_error([&] { read_volume(dir_ / "v.mha", f); }, dir_ / "v.mha", "drop --dims");
  expect_error([&] { read_volume(dir_ / "v.bin", std::nullopt); }, dir_ / "v.bin", "needs --dims");
}

// Through the CLI: a .mha renders; a lying one exits non-zero with one line and no image.
TEST_F(VolumeFormats, Cli) {
  // A 16³ ball of value 100 in 0: the iso-surface 50 is a sphere.
  std::string ball;
  for (int k = 0; k < 16; ++k)
    for (int j = 0; j < 16; ++j)
      for (int i = 0; i < 16; ++i) {
        const float r = std::sqrt(float((i - 7.5) * (i - 7.5) + (j - 7.5) * (j - 7.5) + (k - 7.5) * (k - 7.5)));
        ball += bytes_of(std::int16_t(r < 5 ? 100 : 0), true);
      }
  const std::string header = "NDims = 3\nDimSize = 16 16 16\nElementType = MET_SHORT\nElementSpacing = 1 1 1\n"
                             "BinaryDataByteOrderMSB = True\nElementDataFile = LOCAL\n";
  write("ball.mha", header + ball);
  const fs::path png = dir_ / "ball.png";
  const test::CliResult ok = test::run_pss("volume " + (dir_ / "ball.mha").string() + " --iso 50 --size 64x64 -o " +
                                           png.string());
  EXPECT_EQ(ok.exit_code, 0) << ok.err;
  EXPECT_TRUE(fs::exists(png));
  write("lie.mha", header + ball.substr(0, ball.size() - 2));
  const fs::path bad = dir_ / "lie.png";
  const test::CliResult r = test::run_pss("volume " + (dir_ / "lie.mha").string() + " --iso 50 -o " + bad.string());
  EXPECT_NE(r.exit_code, 0);
  EXPECT_EQ(test::line_count(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("lie.mha"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(bad));
  // --skip on the CLI: the .mha read as raw past its header.
  const std::size_t header_bytes = header.size();
  write("ball.bin", header + ball);
  const test::CliResult s = test::run_pss("volume " + (dir_ / "ball.bin").string() + " --dims 16x16x16 --type int16 " +
                                          "--endian big --skip " + std::to_string(header_bytes) +
                                          " --iso 50 --size 64x64 -o " + (dir_ / "skip.png").string());
  EXPECT_EQ(s.exit_code, 0) << s.err;
  const test::CliResult w = test::run_pss("volume " + (dir_ / "ball.bin").string() + " --dims 16x16x16 --type int16 " +
                                          "--skip " + std::to_string(header_bytes + 1) + " --iso 50 -o " +
                                          (dir_ / "w.png").string());
  EXPECT_NE(w.exit_code, 0);
  EXPECT_EQ(test::line_count(w.err), 1) << w.err;
  EXPECT_FALSE(fs::exists(dir_ / "w.png"));
}

}  // namespace
}  // namespace pss
