// The library's volume settings (what the CLI, a viewer and the Python module share): the
// documented defaults resolved in the volume's voxel size, and one-line refusals.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "pss/core/error.hpp"
#include "support/volumes.hpp"

namespace pss {
namespace {

Volume sphere_volume(vec3 spacing) {
  test::SampleVolumeOptions o;
  o.dims = ivec3(24);
  o.spacing = spacing;
  return test::sample_volume(test::sphere_distance(vec3(12.0f) * spacing, 6.0f * spacing.x), o);
}

std::string refusal(const VolumeSettings& s, Volume volume = sphere_volume(vec3(1.0f))) {
  Stats stats;
  try {
    prepare_volume(std::move(volume), s, stats);
  } catch (const Error& e) {
    return e.what();
  }
  return {};
}

TEST(VolumeSettings, DefaultsResolveInTheVoxelSize) {
  // Voxels 0.5 × 0.5 × 2: u = (0.5·0.5·2)^(1/3) = 0.794.
  const vec3 spacing(0.5f, 0.5f, 2.0f);
  VolumeSettings s;
  s.iso = 0;
  Stats stats;
  const PreparedVolume v = prepare_volume(sphere_volume(spacing), s, stats);
  const float u = std::cbrt(0.5f);
  EXPECT_NEAR(v.params.h, 2 * u, 1e-5f);
  EXPECT_NEAR(v.params.step, 0.75f * 2 * u, 1e-5f);
  EXPECT_NEAR(v.params.radius, 1.5f * 2 * u, 1e-5f);
  EXPECT_NEAR(v.params.epsilon, 0.1f * u, 1e-6f);
  EXPECT_EQ(v.params.method, VolumeMethod::predictor_corrector);
  EXPECT_EQ(v.feature.kind, FeatureKind::iso);
  EXPECT_GT(v.cells.crossed_count, 0);
}

TEST(VolumeSettings, RefusesWhatHasNoSurfaceOrNoMeaning) {
  VolumeSettings outside;
  outside.iso = 1000;  // the distance field spans about [−6, 15]
  const std::string iso = refusal(outside);
  EXPECT_NE(iso.find("iso-value 1000"), std::string::npos) << iso;
  EXPECT_NE(iso.find("lies outside"), std::string::npos) << iso;

  VolumeSettings tiny_h;
  tiny_h.h = 0.4f;  // below kMinVolumeH
  EXPECT_NE(refusal(tiny_h).find("h (voxels)"), std::string::npos);
  VolumeSettings nan_alpha;
  nan_alpha.alpha = NAN;
  EXPECT_NE(refusal(nan_alpha).find("alpha"), std::string::npos);
  VolumeSettings wide;
  wide.radius = 5;
  EXPECT_NE(refusal(wide).find("radius"), std::string::npos);
  VolumeSettings gradient;
  gradient.gradient = true;
  gradient.iso = NAN;  // not used for gradient surfaces
  EXPECT_EQ(refusal(gradient), "");

  // A Volume made in code with a spacing no reader would take (a negative one crashed).
  VolumeSettings zero;
  zero.iso = 0;
  for (const vec3 spacing : {vec3(-1, 1, 1), vec3(1, 0, 1), vec3(1, 1, INFINITY)}) {
    Volume flipped = sphere_volume(vec3(1.0f));
    flipped.spacing = spacing;
    EXPECT_NE(refusal(zero, std::move(flipped)).find("is not three positive numbers"), std::string::npos);
  }
}

}  // namespace
}  // namespace pss
