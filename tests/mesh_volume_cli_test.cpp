// `pss mesh` of a volume as a user runs it: a raw or headed file's iso- or gradient surface
// in world units; the summary and --stats say what it is; each of the volume's flags reaches
// the mesh; flags of the other kind of data, and bad input, get one line and no output.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>

#include "pss/mesh/triangle_mesh.hpp"
#include "support/cli.hpp"
#include "support/mesh_readers.hpp"
#include "support/volumes.hpp"

namespace pss {
namespace {

const vec3 kCenter(15.7f, 16.2f, 15.4f);
constexpr float kRadius = 9;

class MeshVolumeCli : public test::CliTest {
 protected:
  // A ball of radius 9 in a 32³ uint8 volume: 100 − 40·(distance to the sphere), its
  // surface the iso-value 100; raw (with the flags that read it) or NRRD with `spacing`.
  std::string raw() {
    write("ball.raw", test::uint8_raw_bytes(test::sphere_distance(kCenter, kRadius), ivec3(32)));
    return path("ball.raw") + " --dims 32x32x32 --type uint8";
  }
  std::string nrrd(float spacing) {
    char header[200];
    std::snprintf(header, sizeof header,
                  "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 32 32 32\nspacings: %g %g %g\nencoding: raw\n\n",
                  double(spacing), double(spacing), double(spacing));
    return write("ball.nrrd", header + test::uint8_raw_bytes(test::sphere_distance(kCenter, kRadius), ivec3(32)));
  }
  test::CliResult mesh(const std::string& input, const std::string& output, const std::string& flags) {
    return test::run_pss("mesh " + input + " -o " + path(output) + " --progress never " + flags);
  }
  nlohmann::json stats(const std::string& name) {
    std::ifstream in(path(name));
    return nlohmann::json::parse(in);
  }
};

// The largest distance of a vertex to the sphere of radius `scale`·R about `scale`·centre.
float worst_distance(const TriangleMesh& m, float scale = 1) {
  float worst = 0;
  for (const vec3& p : m.positions)
    worst = std::max(worst, std::abs(glm::length(p - scale * kCenter) - scale * kRadius));
  return worst;
}

// The shipped tooth as a CT of slices six times its pixels: closed, as its mesh on a cubic
// grid and Flying Edges' are (the lattice's metric, docs/paper-notes.md; with balls round
// in space it had 92 parts and 410 boundary edges, with the hit test's reach along the
// normal in space 48).
// Slices 6x their pixels, and pixels 6x their slices: on the second, corners one cube from
// the surface projected onto sheets several voxels away, and the jumps left holes.
TEST_F(MeshVolumeCli, TheToothInThickSlicesIsClosed) {
  const std::string tooth = std::string(PSS_SOURCE_DIR) + "/data/tooth_103x94x161_uint8.raw";
  for (const std::string spacing : {"0.5,0.5,3", "3,3,0.5"}) {
    SCOPED_TRACE(spacing);
    const test::CliResult r = mesh(tooth + " --dims 103x94x161", "m.ply", "--iso 125 --spacing " + spacing);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const TriangleMesh m = test::read_mesh(path("m.ply"));
    const MeshTopology shape = topology(m);
    EXPECT_TRUE(shape.watertight()) << shape.boundary_edges << " boundary edges";
    EXPECT_LE(shape.components, 6);  // Flying Edges: 3
    Aabb box;
    for (const vec3& p : m.positions) box.grow(p);
    const vec3 extent = box.hi - box.lo;  // 161 slices over 103 pixels
    if (spacing == "0.5,0.5,3")
      EXPECT_GT(extent.z, 2.0f * extent.x);
    else
      EXPECT_LT(extent.z, 0.5f * extent.x);
    // Every normal faces as its triangles do, also where a merge turned them (within 60°).
    TriangleMesh turned = m;
    EXPECT_EQ(normals_follow_winding(turned), 0);
  }
}

TEST_F(MeshVolumeCli, ARawVolumeGivesItsIsoSurface) {
  const test::CliResult r = mesh(raw(), "m.ply", "--iso 100 --stats " + path("s.json"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const TriangleMesh m = test::read_mesh(path("m.ply"));
  const MeshTopology shape = topology(m);
  EXPECT_TRUE(shape.watertight());
  EXPECT_EQ(shape.euler_characteristic(), 2);
  EXPECT_LT(worst_distance(m), 0.15f);
  EXPECT_GT(enclosed_volume(m), 0);  // outward: towards lower values
  EXPECT_NE(r.out.find("volume 32x32x32"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find(std::to_string(m.triangles.size()) + " triangles, 1 component, watertight"), std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("iso-surface 100 by the predictor-corrector, h = 2 voxels, cell 1"), std::string::npos) << r.out;
  const nlohmann::json s = stats("s.json");
  EXPECT_EQ(s["command"], "mesh");
  EXPECT_EQ(s["volume"]["feature"]["kind"], "iso");
  EXPECT_FLOAT_EQ(s["volume"]["feature"]["iso"].get<float>(), 100);
  EXPECT_FLOAT_EQ(s["cell"].get<float>(), 1);
  EXPECT_EQ(s["mesh"]["triangles"], m.triangles.size());
  EXPECT_EQ(s["mesh"]["watertight"], true);
  EXPECT_GT(s["band"]["corners"].get<int>(), 0);
  EXPECT_TRUE(s["seconds"].contains("mesh vertices")) << s["seconds"].dump();
  const long long merged = s["band"]["collapsed_vertices"].get<long long>();
  EXPECT_GT(merged, 0);
  EXPECT_NE(r.out.find(std::to_string(merged) + " vertices merged into neighbours"), std::string::npos) << r.out;
}

// A header's spacing puts the mesh in world units; the default cell is the voxel, and h
// and the cell given follow it.
TEST_F(MeshVolumeCli, AHeadedVolumesSpacingScalesTheMesh) {
  const std::string input = nrrd(2);
  ASSERT_EQ(mesh(input, "m.obj", "--iso 100 --stats " + path("s.json")).exit_code, 0);
  const TriangleMesh m = test::read_mesh(path("m.obj"));
  EXPECT_TRUE(topology(m).watertight());
  EXPECT_LT(worst_distance(m, 2), 0.3f);
  const nlohmann::json s = stats("s.json");
  EXPECT_FLOAT_EQ(s["cell"].get<float>(), 2);
  EXPECT_FLOAT_EQ(s["volume"]["params"]["h"].get<float>(), 4);  // 2 voxels
}

// Every flag of the volume's PSS reaches the mesh.
TEST_F(MeshVolumeCli, EachVolumeFlagChangesTheMesh) {
  const std::string input = raw();
  ASSERT_EQ(mesh(input, "base.ply", "--iso 100").exit_code, 0);
  const std::string base = read(path("base.ply"));
  const std::size_t triangles = test::read_mesh(path("base.ply")).triangles.size();

  ASSERT_EQ(mesh(input, "fine.ply", "--iso 100 --cell 0.5 --stats " + path("fine.json")).exit_code, 0);
  EXPECT_GT(test::read_mesh(path("fine.ply")).triangles.size(), 3 * triangles);
  EXPECT_FLOAT_EQ(stats("fine.json")["cell"].get<float>(), 0.5f);

  ASSERT_EQ(mesh(input, "h.ply", "--iso 100 --h 1.5 --stats " + path("h.json")).exit_code, 0);
  EXPECT_FLOAT_EQ(stats("h.json")["volume"]["params"]["h"].get<float>(), 1.5f);
  EXPECT_TRUE(read(path("h.ply")) != base);
  EXPECT_LT(worst_distance(test::read_mesh(path("h.ply"))), 0.2f);

  // The flags `pss volume` takes, each its own mesh, and --stats says each was used.
  struct Case {
    const char* flags;
    const char* key;
    float value;
  };
  for (const Case& c : {Case{"--radius 1.25", "radius", 2.5f}, Case{"--alpha 0.5", "alpha", 0.5f},
                        Case{"--error 0.05", "epsilon", 0.05f}}) {
    SCOPED_TRACE(c.flags);
    ASSERT_EQ(mesh(input, "f.ply", std::string("--iso 100 ") + c.flags + " --stats " + path("f.json")).exit_code, 0);
    EXPECT_FLOAT_EQ(stats("f.json")["volume"]["params"][c.key].get<float>(), c.value);
    EXPECT_TRUE(read(path("f.ply")) != base);
  }
  ASSERT_EQ(mesh(input, "k.ply", "--iso 100 --smoothing 0.8 --stats " + path("k.json")).exit_code, 0);
  EXPECT_FLOAT_EQ(stats("k.json")["volume"]["feature"]["smoothing"].get<float>(), 0.8f);
  EXPECT_TRUE(read(path("k.ply")) != base);
  ASSERT_EQ(mesh(input, "p.ply", "--iso 100 --method predictor --stats " + path("p.json")).exit_code, 0);
  EXPECT_EQ(stats("p.json")["volume"]["params"]["method"], "predictor");
  EXPECT_TRUE(read(path("p.ply")) != base);
  // Another iso-value is another sphere: 100 − 40·d = 120 at d = −0.5.
  ASSERT_EQ(mesh(input, "i.ply", "--iso 120").exit_code, 0);
  const TriangleMesh inner = test::read_mesh(path("i.ply"));
  float worst = 0;
  for (const vec3& p : inner.positions) worst = std::max(worst, std::abs(glm::length(p - kCenter) - (kRadius - 0.5f)));
  EXPECT_LT(worst, 0.2f);
}

// The gradient surface of a smooth step is its steepest sheet: a ball's sphere. Of two
// balls, of contrast 200 and 100, the fainter's edge has θ2 = (100/200)² = 0.25: meshed
// below that threshold, not at the default 0.5.
TEST_F(MeshVolumeCli, AGradientSurfaceIsMeshedAboveItsThreshold) {
  const vec3 faint = kCenter + vec3(26, 0, 0);
  test::SampleVolumeOptions o;
  o.dims = ivec3(56, 32, 32);
  const test::Field strong = test::smooth_indicator(test::sphere_distance(kCenter, kRadius), 200, 0.7f);
  const test::Field weak = test::smooth_indicator(test::sphere_distance(faint, kRadius), 100, 0.7f);
  std::string bytes;
  for (const float x : test::sample_volume({[&](vec3 p) { return strong.value(p) + weak.value(p); },
                                            [&](vec3 p) { return strong.gradient(p) + weak.gradient(p); }, 0},
                                           o).values)
    bytes.push_back(char(std::uint8_t(std::lround(x))));
  const std::string input = write("steps.raw", bytes) + " --dims 56x32x32 --type uint8";
  const test::CliResult r = mesh(input, "g.ply", "--gradient --stats " + path("g.json"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("gradient surface (threshold 0.5)"), std::string::npos) << r.out;
  const TriangleMesh m = test::read_mesh(path("g.ply"));
  EXPECT_EQ(topology(m).components, 1);
  EXPECT_TRUE(topology(m).watertight());
  EXPECT_LT(worst_distance(m), 0.3f);
  EXPECT_EQ(stats("g.json")["volume"]["feature"]["kind"], "gradient");

  ASSERT_EQ(mesh(input, "t.ply", "--gradient --threshold 0.1 --stats " + path("t.json")).exit_code, 0);
  EXPECT_FLOAT_EQ(stats("t.json")["volume"]["feature"]["threshold"].get<float>(), 0.1f);
  const TriangleMesh both = test::read_mesh(path("t.ply"));
  const MeshTopology shape = topology(both);
  EXPECT_EQ(shape.components, 2);
  EXPECT_TRUE(shape.watertight());
  float worst = 0;
  for (const vec3& p : both.positions)
    worst = std::max(worst, std::min(std::abs(glm::length(p - kCenter) - kRadius),
                                     std::abs(glm::length(p - faint) - kRadius)));
  EXPECT_LT(worst, 0.3f);
  // 0 is a threshold too (it was taken for none given, and 0.5 used).
  const test::CliResult zero = mesh(input, "z.ply", "--gradient --threshold 0 --stats " + path("z.json"));
  ASSERT_EQ(zero.exit_code, 0) << zero.err;
  EXPECT_NE(zero.out.find("gradient surface (threshold 0)"), std::string::npos) << zero.out;
  EXPECT_EQ(stats("z.json")["volume"]["feature"]["threshold"].get<float>(), 0.0f);
}

TEST_F(MeshVolumeCli, TheMeshIsTheSameForAnyThreadCount) {
  const std::string input = raw();
  ASSERT_EQ(mesh(input, "one.ply", "--iso 100 --threads 1").exit_code, 0);
  ASSERT_EQ(mesh(input, "two.ply", "--iso 100 --threads 2").exit_code, 0);
  EXPECT_TRUE(read(path("one.ply")) == read(path("two.ply")));
}

TEST_F(MeshVolumeCli, FlagsOfTheOtherKindAndBadInputGetOneLineAndNoOutput) {
  const std::string volume = raw();
  const std::string out = path("m.ply");
  for (const char* flag : {"--rho 2", "--support global", "--surface apss", "--normals estimate",
                           "--outliers keep", "--iterations 2", "--borders clip"})
    expect_clean_failure("mesh " + volume + " --iso 100 -o " + out + " " + flag,
                         std::string(flag).substr(0, std::string(flag).find(' ')) + " applies to point clouds only",
                         out);
  write("cloud.xyz", "0 0 0\n1 0 0\n0 1 0\n1 1 0.1\n");
  for (const char* flag : {"--iso 3", "--gradient", "--method predictor", "--radius 2", "--alpha 0.5",
                           "--smoothing 1", "--error 0.2", "--threshold 0.3"})
    expect_clean_failure("mesh " + path("cloud.xyz") + " -o " + out + " " + flag,
                         std::string(flag).substr(0, std::string(flag).find(' ')) + " applies to volumes only", out);
  expect_clean_failure("mesh " + volume + " -o " + out, "choose the surface", out);
  expect_clean_failure("mesh " + volume + " --iso 100 --threshold 0.3 -o " + out, "--threshold", out);
  expect_clean_failure("mesh " + volume + " --iso 100 --threshold 0 -o " + out, "--threshold", out);
  expect_clean_failure("mesh " + volume + " --iso 100 --h 0.3 -o " + out, "--h", out);
  expect_clean_failure("mesh " + volume + " --iso 300 -o " + out, "ball.raw", out);  // no surface
  expect_clean_failure("mesh " + volume + " --iso 100 --cell 1e-3 -o " + out, "too small for this volume", out);
  expect_clean_failure("mesh " + path("ball.raw") + " --dims 32x32x31 --type uint8 --iso 100 -o " + out, "ball.raw",
                       out);
  expect_clean_failure("mesh " + volume + " --iso 100 -o " + out + " --stats " + path("s.json") + " --cell 1e-3",
                       "too small", path("s.json"));
}

}  // namespace
}  // namespace pss
