// The shipped scans (issue 7): pss's hits against an independent iso-surface of the same
// voxels (tests/support/iso_reference: the trilinear interpolant's first crossing along each
// ray, and a marching-tetrahedra mesh for distances), the field's standard on real data.
// At the documented defaults, from two views each: no surface missing and none made up
// away from the silhouette's rim (≤ 0.5 % and ≤ 1 % of the object's pixels; at the rim a
// surface smoothed at the scale h may move the outline by a pixel), and hits within half a
// voxel of the mesh on average. The iso-values are sensible ones for each scan: valleys of
// its histogram (pss info) and the levels the issue measured.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "pss/io/volume_file.hpp"
#include "support/iso_reference.hpp"
#include "support/volumes.hpp"

namespace pss {
namespace {

struct Scan {
  const char* file;
  std::optional<RawVolumeFormat> raw;
  std::vector<float> isos;
};

void expect_agreement(const Scan& scan) {
  const Volume volume = read_volume(std::filesystem::path(PSS_SOURCE_DIR "/data") / scan.file, scan.raw);
  for (const float iso : scan.isos) {
    const PreparedVolume prepared = test::prepare_iso(volume, iso);
    const test::ReferenceMesh mesh(volume.view(), iso);
    for (const vec2 view : {vec2(30, 10), vec2(200, -30)}) {
      const Camera camera = test::volume_camera(prepared.surface_bounds(), 192, 192, view.x, view.y);
      const test::ReferenceComparison c = test::measure_against_reference(prepared, iso, camera, mesh).comparison;
      const std::string name = std::string(scan.file) + " iso " + std::to_string(int(iso)) + " view " +
                               std::to_string(int(view.x)) + "," + std::to_string(int(view.y));
      std::printf("%s: %lld object pixels; holes %.2f %% (%.2f %% off the rim), phantom %.2f %% (%.2f %%); mean "
                  "distance %.3f voxels\n", name.c_str(), (long long)c.object_pixels, 100 * c.holes,
                  100 * c.interior_holes, 100 * c.phantom, 100 * c.exterior_phantom, c.mean_distance);
      EXPECT_GT(c.object_pixels, 1000) << name;
      EXPECT_LE(c.interior_holes, 0.005) << name;
      // With the rim, where the outline may move by a pixel: 0.1–4.7 % measured (fuel's thin
      // jet the most).
      EXPECT_LE(c.holes, 0.05) << name;
      EXPECT_LE(c.exterior_phantom, 0.01) << name;
      EXPECT_LE(c.mean_distance, 0.5) << name;
      // Nothing drawn in front of the data's first surface, nor a first surface skipped.
      EXPECT_LE(c.in_front, 0.05) << name;
      EXPECT_LE(c.behind, 0.05) << name;
    }
  }
}

// The tooth's background (70–90, noisy) lies just below 110 and above 60: both used to
// fill the box with sheets. 125 is its histogram's valley.
TEST(VolumeRealData, Tooth) {
  expect_agreement({"tooth_103x94x161_uint8.raw", test::uint8_raw(ivec3(103, 94, 161)), {60, 110, 125}});
}
TEST(VolumeRealData, Engine) { expect_agreement({"engine_256x256x128_uint8.nrrd", std::nullopt, {75, 180}}); }
TEST(VolumeRealData, Fuel) { expect_agreement({"fuel_64x64x64_uint8.raw", test::uint8_raw(ivec3(64, 64, 64)), {30, 60}}); }
// Fuel at 100 and bucky at 150–200 are scatters of blobs one or two voxels across, below
// the PSS's feature size h = 2 voxels (§5.1), which it smooths away or merges (see
// docs/benchmarks.md); these levels are the scans' own surfaces.
TEST(VolumeRealData, Bucky) { expect_agreement({"bucky_32x32x32_uint8.raw", test::uint8_raw(ivec3(32, 32, 32)), {60, 100}}); }
TEST(VolumeRealData, Neghip) { expect_agreement({"neghip_64x64x64_uint8.raw", test::uint8_raw(ivec3(64, 64, 64)), {40, 120}}); }

}  // namespace
}  // namespace pss
