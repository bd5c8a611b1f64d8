// N(x), the voxels a projection sums over (volume/projection.hpp), against a brute-force loop
// over every voxel of the volume: the CPU gathers eight voxels of a row at a time in AVX2
// (volume/voxel_gather_avx2.hpp) and must keep exactly the voxels that VoxelWeights keeps,
// in the lattice's order, with the same window and θ up to rounding.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "pss/volume/fields.hpp"
#include "pss/volume/projection.hpp"

namespace pss {
namespace {

struct Gathered {
  vec3 d;
  float window, theta;
};

// Every voxel of the volume, in the lattice's order, that VoxelWeights keeps within the ball.
std::vector<Gathered> brute_force(const FieldView& f, vec3 c, float radius, vec3 n, bool weighted_only) {
  const VoxelWeights weights{1.0f / (radius * radius), n, weighted_only};
  const VolumeView& v = f.volume;
  std::vector<Gathered> out;
  for (int k = 0; k < v.dims.z; ++k)
    for (int j = 0; j < v.dims.y; ++j)
      for (int i = 0; i < v.dims.x; ++i) {
        const vec3 d = v.origin + vec3(float(i), float(j), float(k)) * v.spacing - c;
        if (length2(d) > radius * radius) continue;
        Gathered g{d, 0, 0};
        if (weights(f, d, v.index(i, j, k), g.window, g.theta)) out.push_back(g);
      }
  return out;
}

// A volume of random values with random spacing, so that θ1 takes every value from 0 to 1
// and voxels fall on both sides of the 1e-5 threshold.
VolumeFields random_fields(ivec3 dims, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> value(0.0f, 255.0f), spacing(0.6f, 1.4f);
  Volume volume;
  volume.dims = dims;
  volume.spacing = vec3(spacing(rng), spacing(rng), spacing(rng));
  volume.origin = vec3(-3.0f, 1.5f, 0.25f);
  volume.values.resize(std::size_t(volume.voxel_count()));
  for (float& x : volume.values) x = value(rng);
  VolumeFields fields = compute_fields(std::move(volume));
  set_feature(fields, iso_feature(128.0f, 40.0f));
  return fields;
}

void expect_gathers(const FieldView& f, vec3 c, float radius, vec3 n, bool weighted_only) {
  const std::vector<Gathered> truth = brute_force(f, c, radius, n, weighted_only);
  VoxelNeighbourhood nb;
  nb.gather(f, c, radius, n, weighted_only);
  const int expected = std::min(int(truth.size()), kMaxNeighbours);
  ASSERT_EQ(nb.count, expected) << "centre " << c.x << " " << c.y << " " << c.z << ", radius " << radius;
  for (int i = 0; i < nb.count; ++i) {
    const Gathered& t = truth[std::size_t(i)];
    ASSERT_NEAR(nb.dx[i], t.d.x, 1e-5f) << "voxel " << i;
    ASSERT_EQ(nb.dy[i], t.d.y) << "voxel " << i;
    ASSERT_EQ(nb.dz[i], t.d.z) << "voxel " << i;
    ASSERT_NEAR(nb.window[i], t.window, 1e-5f) << "voxel " << i;
    ASSERT_NEAR(nb.theta[i], t.theta, 1e-5f * (1 + t.theta)) << "voxel " << i;
  }
  for (int i = nb.count; i % PSS_SUM_LANES != 0; ++i) {
    ASSERT_EQ(nb.window[i], 0.0f) << "padding slot " << i;
    ASSERT_EQ(nb.theta[i], 0.0f) << "padding slot " << i;
  }
}

// Centres all over the volume and past its faces, radii whose rows hold 1 to 20 voxels (a
// row of more than 8 takes several loads), normals in every direction, both kinds of gather.
TEST(VolumeGather, KeepsTheVoxelsOfABruteForceLoopInTheLatticeOrder) {
  const VolumeFields fields = random_fields(ivec3(23, 9, 11), 7);
  const FieldView f = fields.view();
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::normal_distribution<float> gauss;
  const auto [lo, hi] = fields.volume.view().bounds();
  int checked = 0, gathered = 0;
  for (float radius : {0.4f, 1.3f, 2.9f, 4.2f, 9.5f}) {
    for (int trial = 0; trial < 60; ++trial) {
      const vec3 u(unit(rng), unit(rng), unit(rng));
      const vec3 c = lo - 2.0f + u * (hi - lo + 4.0f);
      const vec3 n = glm::normalize(vec3(gauss(rng), gauss(rng), gauss(rng)));
      for (bool weighted_only : {true, false}) {
        expect_gathers(f, c, radius, n, weighted_only);
        VoxelNeighbourhood nb;
        nb.gather(f, c, radius, n, weighted_only);
        gathered += nb.count;
        ++checked;
      }
    }
  }
  EXPECT_EQ(checked, 600);
  EXPECT_GT(gathered, 20000);
}

// The last voxels of the array, where eight could not be read past the row: rows that end
// at the volume's last voxel, and rows as short as one voxel there.
TEST(VolumeGather, KeepsTheLastVoxelsOfTheArray) {
  const VolumeFields fields = random_fields(ivec3(5, 4, 3), 3);
  const FieldView f = fields.view();
  const auto [lo, hi] = fields.volume.view().bounds();
  const vec3 n = glm::normalize(vec3(1.0f, 2.0f, -0.5f));
  for (float radius : {0.3f, 1.0f, 2.5f, 20.0f})
    for (bool weighted_only : {true, false}) {
      expect_gathers(f, hi, radius, n, weighted_only);
      expect_gathers(f, hi - vec3(0.1f, 0.0f, 0.0f), radius, n, weighted_only);
      expect_gathers(f, lo, radius, n, weighted_only);
    }
}

// More voxels in the ball than N(x) holds: the first kMaxNeighbours in the lattice's order.
TEST(VolumeGather, KeepsTheFirstVoxelsWhenTheBallHoldsMoreThanItsCapacity) {
  const VolumeFields fields = random_fields(ivec3(20, 20, 20), 5);
  const FieldView f = fields.view();
  const auto [lo, hi] = fields.volume.view().bounds();
  const vec3 c = 0.5f * (lo + hi), n(0.0f, 0.0f, 1.0f);
  const float radius = 6.0f * fields.volume.spacing.x;
  ASSERT_GT(brute_force(f, c, radius, n, false).size(), std::size_t(kMaxNeighbours) + 100);
  expect_gathers(f, c, radius, n, false);
}

}  // namespace
}  // namespace pss
