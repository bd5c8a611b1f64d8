// Hostile parameters and messages (issue 8): every numeric flag of every subcommand refuses
// NaN, infinities and values out of its range with one line naming the flag, exit status 2
// (a usage error) and no output; every message quotes what it echoes printably and briefly.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cfloat>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "pss/core/error.hpp"
#include "pss/core/text.hpp"
#include "support/cli.hpp"

namespace pss {
namespace {

namespace fs = std::filesystem;

TEST(Text, PrintableKeepsPrintableAsciiAndEscapesTheRest) {
  EXPECT_EQ(printable("abc 1.5,2"), "abc 1.5,2");
  EXPECT_EQ(printable("a\nb\rc\td\x1b[31m"), "a\\x0ab\\x0dc\\x09d\\x1b[31m");
  EXPECT_EQ(printable(std::string("\0\x7f\xff", 3)), "\\x00\\x7f\\xff");
  EXPECT_EQ(printable("C:\\x41"), "C:\\\\x41");  // a backslash in the input cannot fake an escape
}

TEST(Text, PrintableCutsLongTextWithAnEllipsis) {
  const std::string big(20'000'000, 'A');
  EXPECT_EQ(printable(big), std::string(kQuotedBytes, 'A') + "…");
  EXPECT_EQ(printable(std::string(kQuotedBytes, 'A')), std::string(kQuotedBytes, 'A'));
  EXPECT_EQ(printable("abcdef", 3), "abc…");
  // Escaping happens after the cut: at most 4 bytes out per byte in.
  EXPECT_LE(printable(std::string(1000, '\n')).size(), 4 * kQuotedBytes + 3);
}

TEST(Text, QuoteWrapsInSingleQuotes) {
  EXPECT_EQ(quote("nan"), "'nan'");
  EXPECT_EQ(quote(""), "''");
  EXPECT_EQ(quote("a\nb"), "'a\\x0ab'");
  EXPECT_EQ(quote("abcdef", 2), "'ab…'");
}

TEST(Text, OneLineEscapesControlBytesOnly) {
  EXPECT_EQ(one_line("--fov: got 'nan…'"), "--fov: got 'nan…'");
  EXPECT_EQ(one_line("a\nb"), "a\\x0ab");
  EXPECT_EQ(one_line(std::string(5000, 'x')).size(), 1024u + std::string("…").size());
  // The bound is on what is printed: 5000 control bytes were 1024 escapes, 4 KiB (found by
  // fuzz/cli.cpp: an unexpected argument of control bytes, echoed by CLI11).
  std::string escapes;  // 256 escapes of 4 bytes: 1024
  for (int i = 0; i < 256; ++i) escapes += "\\x19";
  EXPECT_EQ(one_line(std::string(5000, '\x19')), escapes + "…");
}

// MiB below a GiB, GiB from it, four significant digits (the memory plans' messages).
TEST(Text, ByteSizesInMibAndGib) {
  EXPECT_EQ(byte_size(3.5 * (1 << 20)), "3.5 MiB");
  EXPECT_EQ(byte_size(1023.0 * (1 << 20)), "1023 MiB");
  EXPECT_EQ(byte_size(double(1 << 30)), "1 GiB");
  EXPECT_EQ(byte_size(12.25 * double(1 << 30)), "12.25 GiB");
}

// The numbers a value must be, as the flags' and the Python module's messages name them.
TEST(Text, RangesAsMessagesNameThem) {
  EXPECT_EQ(range_text(0, FLT_MAX, true), "a finite number > 0");
  EXPECT_EQ(range_text(1, FLT_MAX, false), "a finite number >= 1");
  EXPECT_EQ(range_text(-FLT_MAX, 5, false), "a finite number <= 5");
  EXPECT_EQ(range_text(-FLT_MAX, FLT_MAX, false), "a finite number");
  EXPECT_EQ(range_text(0, 180, true), "a finite number > 0 and <= 180");
  EXPECT_EQ(range_text(1, 100, false), "a finite number from 1 to 100");
}

TEST(Text, FileErrorsShowTheNamePrintably) {
  const std::string message = file_error("dir/a\nb.ply", "problem").what();
  EXPECT_EQ(message, "dir/a\\x0ab.ply: problem");
}

class HostileParams : public testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("pss-hostile-params-" + std::to_string(::getpid()));
    fs::create_directories(dir_);
    // A small cloud: 8 x 8 points on the unit sphere, enough for a run that succeeds.
    std::ofstream xyz(dir_ / "cloud.xyz");
    for (int i = 0; i < 16; ++i)
      for (int j = 0; j < 32; ++j) {
        const double t = 3.14159265 * (i + 0.5) / 16, p = 2 * 3.14159265 * j / 32;
        xyz << std::sin(t) * std::cos(p) << ' ' << std::sin(t) * std::sin(p) << ' ' << std::cos(t) << '\n';
      }
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }

  // The usage-error contract: exit 2, one line on stderr naming `flag`, no output file.
  void expect_refused(const std::string& args, const std::string& flag, const std::string& output) {
    const test::CliResult r = test::run_pss(args);
    EXPECT_EQ(r.exit_code, 2) << args << "\n" << r.err;
    EXPECT_EQ(test::line_count(r.err), 1) << args << "\n" << r.err;
    EXPECT_NE(r.err.find(flag), std::string::npos) << args << "\n" << r.err;
    EXPECT_FALSE(fs::exists(output)) << args;
    fs::remove(output);
  }

  fs::path dir_;
};

const std::string kBucky = std::string(PSS_SOURCE_DIR) + "/data/bucky_32x32x32_uint8.raw --dims 32x32x32";

struct BadFlag {
  std::string flag;
  std::vector<std::string> values;
};

// nan, inf, -inf (and their spellings) plus values out of each flag's range.
const std::vector<std::string> kNonFinite = {"nan", "NaN", "inf", "-inf", "infinity", "1e39"};
std::vector<std::string> with_non_finite(std::vector<std::string> out_of_range) {
  out_of_range.insert(out_of_range.end(), kNonFinite.begin(), kNonFinite.end());
  return out_of_range;
}
// The same for a flag that must be > 0: also a positive value that is 0 as a float (--h 1e-50
// meant "estimate h"), and one below float's normal range (--h 1e-45: "epsilon must be a
// positive number").
std::vector<std::string> positive_or_refused(std::vector<std::string> out_of_range) {
  out_of_range.push_back("1e-50");
  out_of_range.push_back("1e-45");
  return with_non_finite(std::move(out_of_range));
}

const std::vector<BadFlag> kComputeFlags = {
    {"--threads", {"nan", "inf", "-inf", "0", "-1", "100000", "1025"}},
};

const std::vector<BadFlag> kRenderFlags = {
    {"--fov", with_non_finite({"0", "0.5", "170.5", "180"})},
    {"--reflectivity", with_non_finite({"-0.1", "1.5"})},
    {"--size", {"nanx8", "8xnan", "infx8", "0x8", "8x-1", "16385x8", "16384x16384", "8192x8193"}},
    {"--view", {"nan,0", "inf,0", "-inf,0", "0,nan", "0,inf", "0,91", "0,-91"}},
};

const std::vector<BadFlag> kVolumeFlags = {
    {"--iso", {"nan", "inf", "-inf", "1e39", "-1e39"}},
    // Below half a voxel the rays' steps multiply (--h 1e-10 hung): the range starts at 0.5.
    {"--h", with_non_finite({"0", "-1", "0.25"})},
    {"--k", with_non_finite({"0", "0.01", "1.5"})},
    {"--radius", with_non_finite({"0", "0.4", "5"})},
    {"--alpha", with_non_finite({"-0.1", "1.1"})},
    {"--smoothing", positive_or_refused({"0", "-1"})},
    {"--error", positive_or_refused({"0", "-1"})},
    {"--threshold", with_non_finite({"-0.5", "1.5"})},
};

// The raw flags, spelled without --dims (each case adds its own).
const std::vector<BadFlag> kRawFlags = {
    {"--spacing", {"nan,1,1", "1,inf,1", "1,1,-inf", "0,1,1", "-1,1,1", "1e39,1,1"}},
    {"--skip", {"nan", "inf", "-1", "-inf", "1e3"}},
};

const BadFlag kDims = {"--dims", {"nanx32x32", "infx32x32", "0x32x32", "-32x32x32", "32x32", "99999999999x1x1"}};

TEST_F(HostileParams, VolumeRefusesEveryBadNumber) {
  const std::string out = path("o.png");
  const std::string base = "volume " + kBucky + " --iso 100 --size 8x8 -o " + out;
  // The command as written succeeds: the refusals below are the flags'.
  ASSERT_EQ(test::run_pss(base).exit_code, 0);
  fs::remove(out);
  for (const auto* table : {&kComputeFlags, &kRenderFlags, &kRawFlags})
    for (const BadFlag& f : *table)
      for (const std::string& v : f.values) expect_refused(base + " " + f.flag + " " + v, f.flag, out);
  for (const BadFlag& f : kVolumeFlags)
    for (const std::string& v : f.values) {
      // --iso replaces the one in `base`; --threshold applies to --gradient surfaces.
      const std::string surface = f.flag == "--iso" ? "" : f.flag == "--threshold" ? " --gradient" : " --iso 100";
      expect_refused("volume " + kBucky + surface + " --size 8x8 -o " + out + " " + f.flag + " " + v, f.flag, out);
    }
  for (const std::string& v : kDims.values)
    expect_refused("volume " + std::string(PSS_SOURCE_DIR) + "/data/bucky_32x32x32_uint8.raw --dims " + v +
                       " --iso 100 --size 8x8 -o " + out, "--dims", out);
}

TEST_F(HostileParams, TheNanFieldOfViewThatCrashedIsAUsageError) {
  expect_refused("volume " + kBucky + " --iso 100 --fov nan -o " + path("o.png"), "--fov", path("o.png"));
  expect_refused("volume " + kBucky + " --iso 100 --threads 100000 -o " + path("o.png"), "--threads", path("o.png"));
}

TEST_F(HostileParams, ExtractRefusesEveryBadNumber) {
  const std::string out = path("o.ply");
  const std::string base = "extract " + kBucky + " --iso 100 -o " + out;
  ASSERT_EQ(test::run_pss(base).exit_code, 0);
  fs::remove(out);
  for (const auto* table : {&kComputeFlags, &kRawFlags})
    for (const BadFlag& f : *table)
      for (const std::string& v : f.values) expect_refused(base + " " + f.flag + " " + v, f.flag, out);
  for (const BadFlag& f : kVolumeFlags)
    for (const std::string& v : f.values) {
      const std::string surface = f.flag == "--iso" ? "" : f.flag == "--threshold" ? " --gradient" : " --iso 100";
      expect_refused("extract " + kBucky + surface + " -o " + out + " " + f.flag + " " + v, f.flag, out);
    }
}

TEST_F(HostileParams, RenderRefusesEveryBadNumber) {
  const std::string out = path("o.png");
  const std::string base = "render " + path("cloud.xyz") + " --size 8x8 -o " + out;
  ASSERT_EQ(test::run_pss(base).exit_code, 0);
  fs::remove(out);
  const std::vector<BadFlag> own = {
      {"--h", positive_or_refused({"0", "-1"})},   {"--rho", positive_or_refused({"0", "-1"})},
      {"--b", positive_or_refused({"0", "-1"})},   {"--epsilon", positive_or_refused({"0", "-1"})},
      {"--iterations", {"nan", "inf", "-inf", "0", "-1", "1e3", "99999999999"}},
      {"--candidates", {"nan", "inf", "0", "-1", "1025", "99999999999", "2.5"}},
  };
  for (const auto* table : {&kComputeFlags, &kRenderFlags, &own})
    for (const BadFlag& f : *table)
      for (const std::string& v : f.values) expect_refused(base + " " + f.flag + " " + v, f.flag, out);
}

TEST_F(HostileParams, ProjectRefusesEveryBadNumber) {
  const std::string out = path("o.ply");
  const std::string base = "project " + path("cloud.xyz") + " -o " + out;
  ASSERT_EQ(test::run_pss(base).exit_code, 0);
  fs::remove(out);
  const std::vector<BadFlag> own = {
      {"--h", positive_or_refused({"0", "-1"})},
      {"--rho", positive_or_refused({"0", "-1"})},
      {"--iterations", {"nan", "inf", "-inf", "0", "101", "1e3"}},
  };
  for (const auto* table : {&kComputeFlags, &own})
    for (const BadFlag& f : *table)
      for (const std::string& v : f.values) expect_refused(base + " " + f.flag + " " + v, f.flag, out);
}

TEST_F(HostileParams, InfoRefusesEveryBadRawNumber) {
  const std::string none = path("none");  // info writes nothing
  for (const BadFlag& f : kRawFlags)
    for (const std::string& v : f.values) expect_refused("info " + kBucky + " " + f.flag + " " + v, f.flag, none);
  for (const std::string& v : kDims.values)
    expect_refused("info " + std::string(PSS_SOURCE_DIR) + "/data/bucky_32x32x32_uint8.raw --dims " + v, "--dims",
                   none);
}

TEST_F(HostileParams, CapsAreInTheMessages) {
  const test::CliResult threads = test::run_pss("project " + path("cloud.xyz") + " -o " + path("o.ply") + " --threads 100000");
  EXPECT_NE(threads.err.find("1024"), std::string::npos) << threads.err;
  const test::CliResult size = test::run_pss("render " + path("cloud.xyz") + " -o " + path("o.png") + " --size 16384x16384");
  EXPECT_NE(size.err.find("67108864"), std::string::npos) << size.err;
  const test::CliResult side = test::run_pss("render " + path("cloud.xyz") + " -o " + path("o.png") + " --size 16385x1");
  EXPECT_NE(side.err.find("16384"), std::string::npos) << side.err;
}

// The refused text is echoed quoted, printable, and cut: one short line whatever was given.
TEST_F(HostileParams, RefusedTextIsEchoedPrintablyAndBriefly) {
  const std::string out = path("o.png");
  const test::CliResult r =
      test::run_pss("render " + path("cloud.xyz") + " -o " + out + " --size \"$(printf '8x8\\033[2J%0500d' 0)\"");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(test::line_count(r.err), 1) << r.err;
  EXPECT_EQ(r.err.find('\033'), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("\\x1b[2J"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("…"), std::string::npos) << r.err;
  EXPECT_LT(r.err.size(), 300u) << r.err;
  // A newline in a value CLI11 itself refuses (not one of the choices) stays on one line.
  const test::CliResult m = test::run_pss("render " + path("cloud.xyz") + " -o " + out + " --secondary \"$(printf 'a\\nb')\"");
  EXPECT_EQ(m.exit_code, 2);
  EXPECT_EQ(test::line_count(m.err), 1) << m.err;
  EXPECT_FALSE(fs::exists(out));
}

TEST_F(HostileParams, AnUnknownNrrdFieldIsNotEchoedWhole) {
  const std::string nrrd = path("big.nrrd");
  {
    std::ofstream f(nrrd, std::ios::binary);
    f << "NRRD0004\ntype: uchar\ndimension: 3\nsizes: 2 2 2\n" << std::string(1'000'000, 'z') << "\x1b"
      << ": 1\nencoding: raw\n\n" << std::string(8, '\0');
  }
  const test::CliResult r = test::run_pss("volume " + nrrd + " --iso 0 -o " + path("o.png"));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(test::line_count(r.err), 1);
  EXPECT_LT(r.err.size(), 400u) << r.err.substr(0, 400);
  EXPECT_NE(r.err.find(nrrd), std::string::npos) << r.err.substr(0, 400);
  EXPECT_NE(r.err.find("…"), std::string::npos) << r.err.substr(0, 400);
  const test::CliResult e = test::run_pss("info " + nrrd);
  EXPECT_LT(e.err.size(), 400u);
}

TEST_F(HostileParams, NonPrintableHeaderBytesAreEscaped) {
  const std::string nrrd = path("esc.nrrd");
  {
    std::ofstream f(nrrd, std::ios::binary);
    f << "NRRD0004\ntype: \x1b[31muchar\ndimension: 3\nsizes: 2 2 2\nencoding: raw\n\n" << std::string(8, '\0');
  }
  const test::CliResult r = test::run_pss("info " + nrrd);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(test::line_count(r.err), 1) << r.err;
  EXPECT_EQ(r.err.find('\033'), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("\\x1b[31muchar"), std::string::npos) << r.err;
}

// The spacing estimate's errors ("the points coincide") name the cloud they are about.
TEST_F(HostileParams, SpacingErrorsNameTheFile) {
  std::ofstream same(path("same.xyz"));  // more than the 15 points the default h needs
  for (int i = 0; i < 20; ++i) same << "1 2 3\n";
  same.close();
  const std::string in = path("same.xyz");
  for (const std::string& args : {"project " + in + " -o " + path("o.ply"), "render " + in + " -o " + path("o.png"),
                                  "info " + in}) {
    const test::CliResult r = test::run_pss(args);
    EXPECT_EQ(r.exit_code, 1) << args;
    EXPECT_EQ(test::line_count(r.err), 1) << r.err;
    EXPECT_NE(r.err.find(in + ": cannot estimate the sample spacing"), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("internal error"), std::string::npos) << r.err;
  }
  EXPECT_FALSE(fs::exists(path("o.ply")));
  EXPECT_FALSE(fs::exists(path("o.png")));
}

// A name longer than the system allows is a message about the output, not an internal error.
TEST_F(HostileParams, AnImpossibleOutputNameIsAFileError) {
  const std::string out = path(std::string(5000, 'n') + ".png");
  const test::CliResult r = test::run_pss("render " + path("cloud.xyz") + " --size 8x8 -o " + out);
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_EQ(test::line_count(r.err), 1) << r.err;
  EXPECT_EQ(r.err.find("internal error"), std::string::npos) << r.err;
  EXPECT_LT(r.err.size(), 1200u);
}

}  // namespace
}  // namespace pss
