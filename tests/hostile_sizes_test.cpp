// Hostile sizes (issue 8): size products that would overflow, headers that claim more than
// the file holds (gzip bombs), parameters whose neighbourhood or lattice outgrows the data,
// and clouds at extreme scales. Each is refused with one line naming the file or flag, no
// output left behind; or, for scales, gives the same surface up to the scale.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include <sys/resource.h>
#include <unistd.h>

#include "pss/core/error.hpp"
#include "pss/io/ply.hpp"
#include "pss/io/volume_file.hpp"
#include "pss/points/project_cloud.hpp"
#include "support/cli.hpp"
#include "support/gzip.hpp"
#include "support/shapes.hpp"

namespace pss {
namespace {

namespace fs = std::filesystem;
using test::gzip;



long peak_rss_kib() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_maxrss;
}

class HostileSizes : public test::CliTest {};

// 2^20 · 2^20 · 2^30 = 2^70 wraps to 0 in int64: the product must be checked, and a size
// message must never print a negative count.
TEST_F(HostileSizes, SizeProductsThatOverflowAreRefused) {
  const std::string huge = "1048576x1048576x1073741824";
  std::string m = test::error_of([&] { parse_dims(huge); });
  EXPECT_NE(m.find("2^31"), std::string::npos) << m;
  EXPECT_EQ(m.find(" -"), std::string::npos) << m;  // no negative count
  m = test::error_of([] { parse_dims("100000x100000x100000"); });
  EXPECT_NE(m.find("1000000000000000 voxels"), std::string::npos) << m;

  const std::string nrrd = write("huge.nrrd", "NRRD0004\ntype: uchar\ndimension: 3\nsizes: 1048576 1048576 1073741824\n"
                                              "encoding: raw\n\n");
  m = test::error_of([&] { read_nrrd(nrrd); });
  EXPECT_NE(m.find(nrrd), std::string::npos) << m;
  EXPECT_NE(m.find("2^31"), std::string::npos) << m;
  const std::string mha = write("huge.mha", "ObjectType = Image\nNDims = 3\nDimSize = 1048576 1048576 1073741824\n"
                                            "ElementType = MET_UCHAR\nElementDataFile = LOCAL\n");
  m = test::error_of([&] { read_metaimage(mha); });
  EXPECT_NE(m.find(mha), std::string::npos) << m;
  EXPECT_NE(m.find("2^31"), std::string::npos) << m;

  const std::string empty = write("empty.raw", "");
  expect_clean_failure("volume " + empty + " --dims " + huge + " --iso 1 -o " + path("out.png"), "--dims",
                       path("out.png"));
  expect_clean_failure("extract " + nrrd + " --iso 1 -o " + path("out.ply"), nrrd, path("out.ply"));
}

// A 8 GiB claim (2^31 float voxels, within the voxel cap) over a few KB of gzip: refused
// once the stream ends, having allocated about what the stream holds.
TEST_F(HostileSizes, AGzipBombIsRefusedWithoutAllocatingItsClaim) {
  const std::string zeros = gzip(std::string(1 << 16, '\0'));
  const std::string bomb = write("bomb.nrrd", "NRRD0004\ntype: float\ndimension: 3\nsizes: 2048 1024 1024\n"
                                              "encoding: gzip\n\n" + zeros);
  const std::string mha = write("bomb.mha", "ObjectType = Image\nNDims = 3\nDimSize = 2048 1024 1024\n"
                                            "ElementType = MET_FLOAT\nCompressedData = True\n"
                                            "ElementDataFile = LOCAL\n" + zeros);
  const long before = peak_rss_kib();
  std::string m = test::error_of([&] { read_nrrd(bomb); });
  EXPECT_NE(m.find("holds 65536 bytes, the header promises 8589934592"), std::string::npos) << m;
  m = test::error_of([&] { read_metaimage(mha); });
  EXPECT_NE(m.find("holds 65536 bytes, the header promises 8589934592"), std::string::npos) << m;
  EXPECT_LT(peak_rss_kib() - before, 256L * 1024) << "KiB of peak memory for a " << zeros.size() << "-byte file";

  // A 2^40-byte claim is past the voxel cap before any data is looked at.
  const std::string tera = write("tera.nrrd", "NRRD0004\ntype: uchar\ndimension: 3\nsizes: 1024 1024 1048576\n"
                                              "encoding: gzip\n\n" + zeros);
  expect_clean_failure("volume " + tera + " --iso 1 -o " + path("out.png"), "2^31", path("out.png"));
  expect_clean_failure("volume " + bomb + " --iso 1 -o " + path("out.png"), bomb, path("out.png"));
}

// Each candidate of the extraction lattice is a projection: b = h = 1e-5 on a 32³ box was
// 3.2 million per axis (now --h is refused below 0.5); the smallest b the flags allow still
// makes more than the cap, refused with the numbers rather than an internal error.
TEST_F(HostileSizes, AnExtractionLatticePastTheCapIsRefused) {
  std::string ramp;
  for (int i = 0; i < 32 * 32 * 32; ++i) ramp.push_back(char(i % 32 * 8));
  const std::string raw = write("ramp.raw", ramp);
  // --h 0.5 voxel, --k 0.05: b = 0.025, 1240^3 candidates.
  expect_clean_failure("extract " + raw + " --dims 32x32x32 --iso 100 --h 0.5 --k 0.05 -o " + path("out.ply"), "2^28",
                       path("out.ply"));
}

// A neighbourhood wider than the whole cloud is a global fit per point; `--h 1e30` never
// finished.
TEST_F(HostileSizes, ANeighbourhoodWiderThanTheCloudIsRefused) {
  test::SampleOptions o;
  o.count = 500;
  write_ply(path("sphere.ply"), test::sample(test::Sphere{}, o));
  const std::string in = path("sphere.ply"), out = path("out.ply");
  expect_clean_failure("project " + in + " -o " + out + " --h 1e30", "bounding-box diagonal", out);
  expect_clean_failure("project " + in + " -o " + out + " --h 10", "bounding-box diagonal", out);
  expect_clean_failure("render " + in + " -o " + path("out.png") + " --h 1e30", "bounding-box diagonal",
                       path("out.png"));
}

// An h far below the spacing leaves every point alone: that is a failure, not a result.
TEST_F(HostileSizes, ARunThatProjectsNothingSaysSo) {
  test::SampleOptions o;
  o.count = 500;
  write_ply(path("sphere.ply"), test::sample(test::Sphere{}, o));
  expect_clean_failure("project " + path("sphere.ply") + " -o " + path("out.ply") + " --h 1e-6",
                       "no point was projected", path("out.ply"));
  // render's image would be background alone: the same, naming the file.
  expect_clean_failure("render " + path("sphere.ply") + " -o " + path("out.png") + " --h 1e-6",
                       path("sphere.ply") + ": no surface with h = 1e-06", path("out.png"));
}

// Four points: the h estimated from them spans the whole cloud. The refusal names the file,
// in project and render as in mesh.
TEST_F(HostileSizes, ACloudTooSmallForItsNeighbourhoodIsNamed) {
  const std::string four = write("four.xyz", "0 0 0\n1 0 0\n0 1 0\n1 1 0.1\n");
  expect_clean_failure("project " + four + " -o " + path("out.ply") + " --h 5", four + ": the neighbourhood radius",
                       path("out.ply"));
  expect_clean_failure("render " + four + " -o " + path("out.png") + " --h 5", four + ": the neighbourhood radius",
                       path("out.png"));
  // Without --h, too few points for the default h (the 15th neighbour's distance).
  expect_clean_failure("project " + four + " -o " + path("out.ply"), four + ": has 4 points: too few for the default h",
                       path("out.ply"));
}

// A thousand points on a line project nowhere: the error says why, not that h is too small.
TEST_F(HostileSizes, PointsOnALineProjectNowhereAndAreSaidToLieOnALine) {
  std::string line;
  for (int i = 0; i < 1000; ++i) line += std::to_string(0.01 * i) + " " + std::to_string(0.02 * i) + " 0\n";
  const std::string file = write("line.xyz", line);
  expect_clean_failure("project " + file + " -o " + path("out.ply"), file + ": no point was projected", path("out.ply"));
  const test::CliResult r = test::run_pss("project " + file + " -o " + path("out.ply"));
  EXPECT_NE(r.err.find("lie on a line"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("too small"), std::string::npos) << r.err;
}

PointCloud scaled(const PointCloud& c, float s) {
  PointCloud out = c;
  for (vec3& p : out.positions) p *= s;
  return out;
}

// The same noisy sphere in units of 1e30, 1 and 1e-30 projects to the same points up to the
// scale: the library, and the CLI with its estimated h.
TEST_F(HostileSizes, ProjectionDoesNotDependOnTheUnits) {
  test::SampleOptions o;
  o.count = 2000;
  o.noise = 0.01f;
  const PointCloud unit = test::sample(test::Sphere{}, o);
  const float h = test::suggested_h(unit);
  Stats stats;
  const CloudProjection reference = project_cloud(unit, ProjectionParams::from_h(h), Backend::cpu, stats);
  ASSERT_GT(reference.counts.converged, 1900);
  write_ply(path("unit.ply"), unit);
  ASSERT_EQ(test::run_pss("project " + path("unit.ply") + " -o " + path("unit_out.ply")).exit_code, 0);
  const PointCloud cli_reference = read_ply(path("unit_out.ply"));
  for (const float s : {1e30f, 1e-30f}) {
    const CloudProjection r = project_cloud(scaled(unit, s), ProjectionParams::from_h(h * s), Backend::cpu, stats);
    EXPECT_EQ(r.counts.converged, reference.counts.converged) << s;
    double worst = 0;
    for (std::size_t i = 0; i < unit.size(); ++i)
      worst = std::max(worst, double(glm::length(r.cloud.positions[i] / s - reference.cloud.positions[i])));
    EXPECT_LT(worst, 1e-5) << "scale " << s;

    const std::string name = s > 1 ? "big" : "small";
    write_ply(path(name + ".ply"), scaled(unit, s));
    const test::CliResult cli = test::run_pss("project " + path(name + ".ply") + " -o " + path(name + "_out.ply"));
    ASSERT_EQ(cli.exit_code, 0) << cli.err;
    const PointCloud out = read_ply(path(name + "_out.ply"));
    ASSERT_EQ(out.size(), cli_reference.size());
    worst = 0;
    for (std::size_t i = 0; i < out.size(); ++i)
      worst = std::max(worst, double(glm::length(out.positions[i] / s - cli_reference.positions[i])));
    // The CLI estimates h from the data at each scale, so the iterations stop within their
    // tolerance (1e-3·h) of each other, not at the same rounding.
    EXPECT_LT(worst, 1e-3 * h) << "scale " << s << " through the CLI";
  }
}

}  // namespace
}  // namespace pss
