// Reading volumes: raw with explicit dims/type/spacing/endianness, NRRD attached and
// detached, raw and gzip; and every bad input as a one-line error, through the CLI too
// (no output file left behind).
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <future>
#include <string>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include "pss/core/error.hpp"
#include "pss/io/output_file.hpp"
#include "pss/io/volume_file.hpp"
#include "support/cli.hpp"
#include "support/gzip.hpp"

namespace pss {
namespace {

namespace fs = std::filesystem;
using test::gzip;


void write_bytes(const fs::path& p, const std::string& bytes) {
  std::ofstream out(p, std::ios::binary);
  out << bytes;
}


// 2×3×4 voxels valued i + 10j + 100k.
std::string ramp_uint8() {
  std::string s;
  for (int k = 0; k < 4; ++k)
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 2; ++i) s.push_back(char(i + 10 * j + 100 * k > 255 ? 255 : i + 10 * j + 100 * k));
  return s;
}

std::string error_of(auto&& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(VolumeIo, RawUint8WithSpacing) {
  const test::TestFolder folder;
  const fs::path p = folder.path() / "ramp.raw";
  write_bytes(p, ramp_uint8());
  RawVolumeFormat f;
  f.dims = parse_dims("2x3x4");
  f.spacing = parse_spacing("1,2,0.5");
  const Volume v = read_raw_volume(p, f);
  EXPECT_EQ(v.dims, ivec3(2, 3, 4));
  EXPECT_EQ(v.view().at(1, 2, 1), 121.0f);
  EXPECT_EQ(v.view().position(1, 2, 3), vec3(1.0f, 4.0f, 1.5f));  // origin + (i·sx, j·sy, k·sz)
}

TEST(VolumeIo, RawUint16BigEndianAndFloat32) {
  const test::TestFolder folder;
  const fs::path& d = folder.path();
  std::string big;
  for (int i = 0; i < 8; ++i) {
    const int v = 1000 * i + 1;
    big.push_back(char(v >> 8));
    big.push_back(char(v & 255));
  }
  write_bytes(d / "u16.raw", big);
  RawVolumeFormat f;
  f.dims = ivec3(2, 2, 2);
  f.type = parse_voxel_type("uint16");
  f.big_endian = true;
  EXPECT_EQ(read_raw_volume(d / "u16.raw", f).values[7], 7001.0f);
  std::string floats(8 * 4, '\0');
  for (int i = 0; i < 8; ++i) {
    const float x = -1.5f * float(i);
    std::memcpy(floats.data() + 4 * i, &x, 4);
  }
  write_bytes(d / "f32.raw", floats);
  f.type = VoxelType::float32;
  f.big_endian = false;
  EXPECT_EQ(read_raw_volume(d / "f32.raw", f).values[3], -4.5f);
}

TEST(VolumeIo, NrrdAttachedDetachedAndGzip) {
  const test::TestFolder folder;
  const fs::path& d = folder.path();
  const std::string header =
      "NRRD0004\n# a comment\ntype: uchar\ndimension: 3\nsizes: 2 3 4\nspace dimension: 3\n"
      "space directions: (1,0,0) (0,2,0) (0,0,0.5)\nspace origin: (10,20,30)\nendian: little\n";
  write_bytes(d / "a.nrrd", header + "encoding: raw\n\n" + ramp_uint8());
  write_bytes(d / "g.nrrd", header + "encoding: gzip\n\n" + gzip(ramp_uint8()));
  write_bytes(d / "data.raw", ramp_uint8());
  write_bytes(d / "b.nhdr", header + "encoding: raw\ndata file: data.raw\n");
  // byte skip -1: the voxels are the data's last bytes, whatever comes before them.
  write_bytes(d / "prefixed.raw", "a preamble" + ramp_uint8());
  write_bytes(d / "c.nhdr", header + "encoding: raw\nbyte skip: -1\ndata file: prefixed.raw\n");
  for (const char* name : {"a.nrrd", "g.nrrd", "b.nhdr", "c.nhdr"}) {
    const Volume v = read_volume(d / name, std::nullopt);
    EXPECT_EQ(v.dims, ivec3(2, 3, 4)) << name;
    EXPECT_EQ(v.view().at(1, 1, 2), 211.0f) << name;
    EXPECT_EQ(v.view().position(1, 1, 2), vec3(11.0f, 22.0f, 31.0f)) << name;
  }
  write_bytes(d / "s.nrrd", "NRRD0004\ntype: float\ndimension: 3\nsizes: 1 1 2\nspacings: 1 1 3\nencoding: raw\n"
                            "endian: big\n\n" + std::string("\x3f\x80\x00\x00\x40\x00\x00\x00", 8));
  const Volume s = read_volume(d / "s.nrrd", std::nullopt);
  EXPECT_EQ(s.values[1], 2.0f);
  EXPECT_EQ(s.spacing.z, 3.0f);
}

TEST(VolumeIo, BadInputsAreOneLineErrors) {
  const test::TestFolder folder;
  const fs::path& d = folder.path();
  write_bytes(d / "short.raw", ramp_uint8().substr(1));
  RawVolumeFormat f;
  f.dims = ivec3(2, 3, 4);
  EXPECT_NE(error_of([&] { read_raw_volume(d / "short.raw", f); }).find("holds 23 bytes"), std::string::npos);
  // A byte too many is refused too: the dims or the type are not the file's, and read
  // anyway every slice would shift.
  write_bytes(d / "long.raw", ramp_uint8() + "x");
  EXPECT_NE(error_of([&] { read_raw_volume(d / "long.raw", f); }).find("holds 25 bytes"), std::string::npos);
  EXPECT_NE(error_of([] { parse_dims("0x4x4"); }).find("positive"), std::string::npos);
  EXPECT_NE(error_of([] { parse_dims("100000x100000x100000"); }).find("more than"), std::string::npos);
  EXPECT_NE(error_of([] { parse_dims("4x4"); }).find("XxYxZ"), std::string::npos);
  EXPECT_NE(error_of([] { parse_spacing("1,0,1"); }).find("positive"), std::string::npos);
  const std::string header = "NRRD0004\ntype: uchar\ndimension: 3\nsizes: 2 3 4\n";
  write_bytes(d / "field.nrrd", header + "measurement frame: (1,0,0) (0,1,0) (0,0,1)\nencoding: raw\n\n" + ramp_uint8());
  EXPECT_NE(error_of([&] { read_nrrd(d / "field.nrrd"); }).find("unsupported NRRD field 'measurement frame'"),
            std::string::npos);
  write_bytes(d / "rot.nrrd", header + "space directions: (0,1,0) (1,0,0) (0,0,1)\nencoding: raw\n\n" + ramp_uint8());
  EXPECT_NE(error_of([&] { read_nrrd(d / "rot.nrrd"); }).find("only diagonal"), std::string::npos);
  write_bytes(d / "type.nrrd", "NRRD0004\ntype: int64\ndimension: 3\nsizes: 2 3 4\nencoding: raw\n\n");
  EXPECT_NE(error_of([&] { read_nrrd(d / "type.nrrd"); }).find("unsupported NRRD type"), std::string::npos);
  write_bytes(d / "zero.nrrd", "NRRD0004\ntype: uchar\ndimension: 3\nsizes: 0 3 4\nencoding: raw\n\n");
  EXPECT_NE(error_of([&] { read_nrrd(d / "zero.nrrd"); }).find("positive"), std::string::npos);
  const std::string z = gzip(ramp_uint8());
  write_bytes(d / "trunc.nrrd", header + "encoding: gzip\n\n" + z.substr(0, z.size() / 2));
  EXPECT_NE(error_of([&] { read_nrrd(d / "trunc.nrrd"); }).find("truncated gzip stream"), std::string::npos);
  write_bytes(d / "nofile.nhdr", header + "encoding: raw\ndata file: missing.raw\n");
  EXPECT_NE(error_of([&] { read_nrrd(d / "nofile.nhdr"); }).find("missing.raw"), std::string::npos);
  for (const std::string& m : {error_of([&] { read_raw_volume(d / "short.raw", f); }),
                               error_of([&] { read_nrrd(d / "trunc.nrrd"); })})
    EXPECT_EQ(m.find('\n'), std::string::npos);
}

// A header's detached data file may name anything: a FIFO blocked read_file's open until a
// writer came, for ever (a NRRD or MetaImage header naming one hung pss). Devices and FIFOs
// are refused before the open.
TEST(VolumeIo, DetachedDataThatIsAFifoIsRefusedWithoutWaiting) {
  const test::TestFolder folder;
  const fs::path& d = folder.path();
  const fs::path fifo = d / "fifo.raw";
  fs::remove(fifo);
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  write_bytes(d / "fifo.nhdr", "NRRD0004\ntype: uchar\ndimension: 3\nsizes: 2 3 4\nencoding: raw\ndata file: fifo.raw\n");
  write_bytes(d / "fifo.mhd", "NDims = 3\nDimSize = 2 3 4\nElementType = MET_UCHAR\nElementDataFile = fifo.raw\n");
  for (const char* header : {"fifo.nhdr", "fifo.mhd"}) {
    auto message = std::async(std::launch::async, [&] { return error_of([&] { read_volume(d / header, std::nullopt); }); });
    const bool done = message.wait_for(std::chrono::seconds(5)) == std::future_status::ready;
    if (!done) ::close(::open(fifo.c_str(), O_WRONLY | O_NONBLOCK));  // a writer, so that the reader returns
    EXPECT_TRUE(done) << header << ": the reader waited for a writer of its FIFO";
    EXPECT_NE(message.get().find("fifo.raw: cannot open: not a regular file"), std::string::npos) << header;
  }
  EXPECT_NE(error_of([] { read_file("/dev/zero"); }).find("not a regular file"), std::string::npos);
  fs::remove(fifo);
}

// The CLI: a bad volume is `pss: error: ...` on one line, exit status 1, and no image.
TEST(VolumeIo, CliBadInputsLeaveNoOutput) {
  const test::TestFolder folder;
  const fs::path& d = folder.path();
  write_bytes(d / "short.raw", ramp_uint8().substr(1));
  const std::string header = "NRRD0004\ntype: uchar\ndimension: 3\nsizes: 2 3 4\n";
  const std::string z = gzip(ramp_uint8());
  write_bytes(d / "trunc.nrrd", header + "encoding: gzip\n\n" + z.substr(0, z.size() / 2));
  write_bytes(d / "field.nrrd", header + "thicknesses: 1 1 1\nencoding: raw\n\n" + ramp_uint8());
  const std::string cli = PSS_CLI;
  const fs::path out = d / "out.png";
  const std::string runs[] = {
      cli + " volume " + (d / "short.raw").string() + " --dims 2x3x4 --iso 10 -o " + out.string(),
      cli + " volume " + (d / "short.raw").string() + " --dims 0x3x4 --iso 10 -o " + out.string(),
      cli + " volume " + (d / "short.raw").string() + " --dims 9999999x9999999x9999999 --iso 10 -o " + out.string(),
      cli + " volume " + (d / "trunc.nrrd").string() + " --iso 10 -o " + out.string(),
      cli + " volume " + (d / "field.nrrd").string() + " --iso 10 -o " + out.string(),
      cli + " extract " + (d / "trunc.nrrd").string() + " --iso 10 -o " + (d / "out.ply").string(),
  };
  for (const std::string& run : runs) {
    const fs::path log = d / "log.txt";
    const int status = std::system((run + " > " + log.string() + " 2>&1").c_str());
    EXPECT_NE(status, 0) << run;
    const std::string text = read_file(log);
    // A bad --dims is a usage error ("pss volume: error: --dims: ..."), the rest the file's.
    EXPECT_TRUE(text.rfind("pss: error: ", 0) == 0 || text.rfind("pss volume: error: --dims: ", 0) == 0) << text;
    EXPECT_EQ(text.find('\n'), text.size() - 1) << text;
    EXPECT_FALSE(fs::exists(out)) << run;
    EXPECT_FALSE(fs::exists(d / "out.ply")) << run;
  }
}

}  // namespace
}  // namespace pss
