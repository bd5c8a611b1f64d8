// N(x), the voxels a projection sums over (volume/projection.hpp), against a brute-force loop
// over every voxel of the volume: the CPU gathers eight voxels of a row at a time in AVX2
// (volume/voxel_gather_avx2.hpp), the GPU one at a time, and both must keep the voxels that
// VoxelWeights keeps, in the lattice's order, with the same window and θ, up to rounding
// (which decides the voxels on the ball's surface, of window ~0).
#include <gtest/gtest.h>

#include <sys/mman.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
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

// Every voxel of the volume, in the lattice's order, that VoxelWeights keeps within the ball,
// round in the lattice's metric: one step along any axis measures u.
std::vector<Gathered> brute_force(const FieldView& f, vec3 c, float radius, vec3 n, bool weighted_only) {
  const VolumeView& v = f.volume;
  const float u = v.voxel_size();
  const VoxelWeights weights{1.0f / (radius * radius), n, weighted_only, u / v.spacing};
  std::vector<Gathered> out;
  for (int k = 0; k < v.dims.z; ++k)
    for (int j = 0; j < v.dims.y; ++j)
      for (int i = 0; i < v.dims.x; ++i) {
        const vec3 d = v.origin + vec3(float(i), float(j), float(k)) * v.spacing - c;
        if (length2(d / v.spacing) * u * u > radius * radius) continue;
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

// Whether a voxel lies where rounding decides: on the ball's surface (window ~0) or, in the
// predictor's gather, at the θ threshold. The AVX2 gather computes d² and the window with
// FMAs, the brute force without, so such a voxel may be in one list and not the other.
bool on_a_boundary(const Gathered& g, bool weighted_only) {
  return g.window < 1e-5f || (weighted_only && g.theta < 1.01e-5f);
}

// The voxels a gather keeps, off the boundaries.
std::vector<Gathered> kept(const VoxelNeighbourhood& nb, bool weighted_only) {
  std::vector<Gathered> out;
  for (int i = 0; i < nb.count; ++i) {
    const Gathered g{vec3(nb.dx[i], nb.dy[i], nb.dz[i]), nb.window[i], nb.theta[i]};
    if (!on_a_boundary(g, weighted_only)) out.push_back(g);
  }
  return out;
}

enum class Path { dispatched, scalar };

// Compares N(x) gathered along `path` with the brute force: the same voxels in the same order
// off the boundaries, the same offsets, window and θ; the padding zero. Returns how many it
// gathered.
int expect_gathers(const FieldView& f, vec3 c, float radius, vec3 n, bool weighted_only, Path path) {
  std::vector<Gathered> truth = brute_force(f, c, radius, n, weighted_only);
  if (truth.size() > std::size_t(kMaxNeighbours)) truth.resize(std::size_t(kMaxNeighbours));
  VoxelNeighbourhood nb;
  if (path == Path::dispatched) nb.gather(f, c, radius, n, weighted_only);
  else nb.gather_scalar(f, c, radius, n, weighted_only);
  const std::vector<Gathered> got = kept(nb, weighted_only);
  std::erase_if(truth, [&](const Gathered& g) { return on_a_boundary(g, weighted_only); });
  EXPECT_LE(nb.count - int(got.size()), 2 + nb.count / 50) << "voxels on a boundary";
  const auto where = [&] {
    return ::testing::Message() << "centre " << c.x << " " << c.y << " " << c.z << ", radius " << radius
                                << (weighted_only ? ", weighted only" : "");
  };
  EXPECT_EQ(got.size(), truth.size()) << where();
  for (std::size_t i = 0; i < std::min(got.size(), truth.size()); ++i) {
    const Gathered &g = got[i], &t = truth[i];
    EXPECT_NEAR(g.d.x, t.d.x, 1e-5f) << where() << ", voxel " << i;
    EXPECT_EQ(g.d.y, t.d.y) << where() << ", voxel " << i;
    EXPECT_EQ(g.d.z, t.d.z) << where() << ", voxel " << i;
    EXPECT_NEAR(g.window, t.window, 1e-5f) << where() << ", voxel " << i;
    if (!(std::abs(g.theta - t.theta) <= 1e-5f * (1 + t.theta))) {
      ADD_FAILURE() << where() << ", voxel " << i << ": θ " << g.theta << " against " << t.theta;
      break;
    }
  }
  for (int i = nb.count; i % PSS_SUM_LANES != 0; ++i) {
    EXPECT_EQ(nb.window[i], 0.0f) << "padding slot " << i;
    EXPECT_EQ(nb.theta[i], 0.0f) << "padding slot " << i;
  }
  return nb.count;
}

// Centres all over the volume and past its faces, and on lattice points (voxels then lie
// exactly on the ball's surface); radii whose rows hold 1 to 20 voxels (a row of more than 8
// takes several loads); normals in every direction; both kinds of gather, along the path
// this CPU takes (AVX2 where it has it) and the scalar walk of the GPU.
TEST(VolumeGather, KeepsTheVoxelsOfABruteForceLoopInTheLatticeOrder) {
  const VolumeFields fields = random_fields(ivec3(23, 9, 11), 7);
  const FieldView f = fields.view();
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::normal_distribution<float> gauss;
  const auto [lo, hi] = fields.volume.view().bounds();
  std::uniform_int_distribution<int> i(0, 22), j(0, 8), k(0, 10);
  int checked = 0, gathered = 0;
  for (float radius : {0.4f, 1.3f, 2.9f, 4.2f, 9.5f}) {
    for (int trial = 0; trial < 60; ++trial) {
      const vec3 u(unit(rng), unit(rng), unit(rng));
      const vec3 c = trial % 4 == 0 ? fields.volume.view().position(i(rng), j(rng), k(rng))
                                    : lo - 2.0f + u * (hi - lo + 4.0f);
      const vec3 n = glm::normalize(vec3(gauss(rng), gauss(rng), gauss(rng)));
      for (bool weighted_only : {true, false})
        for (Path path : {Path::dispatched, Path::scalar}) {
          gathered += expect_gathers(f, c, radius, n, weighted_only, path);
          ++checked;
        }
    }
  }
  EXPECT_EQ(checked, 1200);
  EXPECT_GT(gathered, 40000);
  std::printf("[ the dispatched gather ran the %s path ]\n", cpu::has_avx2() ? "AVX2" : "scalar");
}

// The last voxels of the array, where eight could not be read past the row: rows that end
// at the volume's last voxel, and rows as short as one voxel there. The features end where
// an unreadable page begins, so a read past them stops the test.
TEST(VolumeGather, ReadsNothingPastTheLastVoxel) {
  const VolumeFields fields = random_fields(ivec3(5, 4, 3), 3);
  const std::size_t bytes = fields.features.size() * sizeof(FeatureVoxel);
  const std::size_t page = std::size_t(sysconf(_SC_PAGESIZE));
  const std::size_t pages = (bytes + page - 1) / page + 1;
  void* mapping = mmap(nullptr, pages * page, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  ASSERT_NE(mapping, MAP_FAILED);
  char* guard = static_cast<char*>(mapping) + (pages - 1) * page;
  ASSERT_EQ(mprotect(guard, page, PROT_NONE), 0);
  auto* features = reinterpret_cast<FeatureVoxel*>(guard - bytes);
  std::copy(fields.features.begin(), fields.features.end(), features);
  FieldView f = fields.view();
  f.features = features;

  const auto [lo, hi] = fields.volume.view().bounds();
  const vec3 n = glm::normalize(vec3(1.0f, 2.0f, -0.5f));
  for (float radius : {0.3f, 1.0f, 2.5f, 20.0f})
    for (bool weighted_only : {true, false})
      for (Path path : {Path::dispatched, Path::scalar}) {
        expect_gathers(f, hi, radius, n, weighted_only, path);
        expect_gathers(f, hi - vec3(0.1f, 0.0f, 0.0f), radius, n, weighted_only, path);
        expect_gathers(f, lo, radius, n, weighted_only, path);
      }
  munmap(mapping, pages * page);
}

// Eq. 4's energy over a gathered N(x) against its definition summed over the brute force's
// voxels on a grid of unequal spacing, θ3's distance |M(pᵢ − x0 − t·n)| in the lattice's
// metric (VolumeView::metric), and its derivative, which Brent follows, against the energy's
// central difference.
TEST(VolumeGather, TheCorrectorsEnergyIsItsDefinitionInTheLatticesMetric) {
  const VolumeFields fields = random_fields(ivec3(23, 9, 11), 13);
  const FieldView f = fields.view();
  const VolumeView& v = f.volume;
  const vec3 metric = v.voxel_size() / v.spacing;
  ASSERT_GT(std::max({metric.x, metric.y, metric.z}) / std::min({metric.x, metric.y, metric.z}), 1.2f);
  const auto [lo, hi] = v.bounds();
  const vec3 c = 0.5f * (lo + hi) + vec3(0.13f, -0.07f, 0.05f);
  const vec3 n = glm::normalize(vec3(0.3f, -0.5f, 0.8f));
  const float radius = 2.9f, h = 1.9f, alpha = 0.9f;
  VoxelNeighbourhood nb;
  nb.gather_scalar(f, c, radius, n, false);
  const std::vector<Gathered> voxels = brute_force(f, c, radius, n, false);
  ASSERT_GT(voxels.size(), 50u);
  const detail::CorrectorEnergy<VoxelNeighbourhood> energy{nb, n, h, alpha, v.metric()};
  for (const float t : {-0.8f, -0.1f, 0.0f, 0.35f, 1.2f}) {
    double truth = 0;
    for (const Gathered& g : voxels) {
      const double theta3 = g.window * std::exp(-double(length2((g.d - t * n) * metric)) / double(h * h));
      const double s = double(glm::dot(g.d, n)) - t;
      truth += (alpha * g.theta + (1 - alpha) * theta3) * s * s;
    }
    float derivative = 0, unused = 0;
    EXPECT_NEAR(energy(t, derivative), truth, 1e-4 * (1 + truth)) << "t = " << t;
    const float dt = 1e-2f;
    const double numeric = (double(energy(t + dt, unused)) - double(energy(t - dt, unused))) / (2 * dt);
    EXPECT_NEAR(derivative, numeric, 1e-2 * (1 + std::abs(numeric))) << "t = " << t;
  }
}

// More voxels in the ball than N(x) holds: the first kMaxNeighbours in the lattice's order.
TEST(VolumeGather, KeepsTheFirstVoxelsWhenTheBallHoldsMoreThanItsCapacity) {
  const VolumeFields fields = random_fields(ivec3(28, 28, 28), 5);
  const FieldView f = fields.view();
  const auto [lo, hi] = fields.volume.view().bounds();
  const vec3 c = 0.5f * (lo + hi) + vec3(0.01f, 0.02f, 0.03f), n(0.0f, 0.0f, 1.0f);
  const float radius = 10.5f * fields.volume.spacing.x;
  for (bool weighted_only : {false, true}) {
    ASSERT_GT(brute_force(f, c, radius, n, weighted_only).size(), std::size_t(kMaxNeighbours) + 50);
    for (Path path : {Path::dispatched, Path::scalar})
      EXPECT_EQ(expect_gathers(f, c, radius, n, weighted_only, path), kMaxNeighbours);
  }
}

}  // namespace
}  // namespace pss
