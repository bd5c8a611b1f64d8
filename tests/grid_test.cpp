#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <random>

#include "pss/spatial/uniform_grid.hpp"

namespace pss {
namespace {

TEST(UniformGrid, RangeQueriesEqualBruteForce) {
  std::mt19937 rng(1);
  for (int trial = 0; trial < 8; ++trial) {
    std::uniform_real_distribution<float> u(-1.0f, 1.0f + trial);
    std::vector<vec3> pts(2000 + 500 * trial);
    for (vec3& p : pts) p = vec3(u(rng), u(rng), (trial % 2 ? 1.0f : 0.1f) * u(rng));
    const float radius = 0.05f + 0.05f * trial;
    // Cells of the radius and smaller: queries then span several cells, rows of which the
    // query skips or cuts to the ball's chord.
    const UniformGrid grid(pts, radius / float(1 + trial % 3));
    const GridView view = grid.view();
    for (int q = 0; q < 200; ++q) {
      const vec3 c(u(rng) * 1.2f, u(rng) * 1.2f, u(rng));  // some queries outside the box
      std::vector<int> found;
      view.for_each_in_radius(c, radius, [&](vec3 p, float d2, int i) {
        EXPECT_EQ(p, pts[grid.original_index()[i]]);
        EXPECT_FLOAT_EQ(d2, length2(p - c));
        found.push_back(grid.original_index()[i]);
      });
      std::vector<int> brute;
      for (int i = 0; i < int(pts.size()); ++i)
        if (length2(pts[i] - c) <= radius * radius) brute.push_back(i);
      std::sort(found.begin(), found.end());
      ASSERT_EQ(found, brute) << "trial " << trial << " query " << q;
    }
  }
}

TEST(CountingSort, SortsByKeyStablyWithOneOffsetPerKey) {
  std::mt19937 rng(3);
  for (const std::size_t keys : {std::size_t(1), std::size_t(7), std::size_t(5000)}) {  // more keys than items too
    std::uniform_int_distribution<int> pick(0, int(keys) - 1);
    std::vector<int> key(1000);
    for (int& k : key) k = pick(rng);
    std::vector<int> cell_start, order;
    counting_sort(key, keys, cell_start, order);
    std::vector<int> expected(key.size());
    std::iota(expected.begin(), expected.end(), 0);
    std::stable_sort(expected.begin(), expected.end(), [&](int a, int b) { return key[a] < key[b]; });
    EXPECT_EQ(order, expected);
    ASSERT_EQ(cell_start.size(), keys + 1);
    for (std::size_t k = 0; k < keys; ++k) {
      const auto count = std::count(key.begin(), key.end(), int(k));
      EXPECT_EQ(cell_start[k + 1] - cell_start[k], count) << k;
      for (int slot = cell_start[k]; slot < cell_start[k + 1]; ++slot) EXPECT_EQ(key[order[slot]], int(k));
    }
    EXPECT_EQ(cell_start[0], 0);
  }
  std::vector<int> cell_start, order;
  counting_sort(std::vector<int>{}, 3, cell_start, order);
  EXPECT_EQ(cell_start, std::vector<int>(4, 0));
  EXPECT_TRUE(order.empty());
}

TEST(UniformGrid, CapsTheNumberOfCells) {
  const std::vector<vec3> pts{vec3(0.0f), vec3(1000.0f)};
  const UniformGrid grid(pts, 0.001f, 1 << 20);
  const ivec3 d = grid.dims();
  EXPECT_LE((long long)d.x * d.y * d.z, 1 << 20);
  int found = 0;
  grid.view().for_each_in_radius(vec3(0.0f), 0.5f, [&](vec3, float, int) { ++found; });
  EXPECT_EQ(found, 1);
}

TEST(UniformGrid, CapsCellsFarSmallerThanTheBoxWhoseCountOverflowsAnInteger) {
  // 1e8 cells per axis: 1e24 in all, beyond long long.
  const std::vector<vec3> pts{vec3(0.0f), vec3(1.0f)};
  const UniformGrid grid(pts, 1e-8f, 1 << 20);
  const ivec3 d = grid.dims();
  EXPECT_GE(d.x, 1);
  EXPECT_LE((long long)d.x * d.y * d.z, 1 << 20);
}

TEST(UniformGrid, EmptyAndSinglePoint) {
  const UniformGrid empty(std::vector<vec3>{}, 1.0f);
  int found = 0;
  empty.view().for_each_in_radius(vec3(0.0f), 10.0f, [&](vec3, float, int) { ++found; });
  EXPECT_EQ(found, 0);
  const UniformGrid one(std::vector<vec3>{vec3(1, 2, 3)}, 1.0f);
  one.view().for_each_in_radius(vec3(1, 2, 3), 0.1f, [&](vec3, float, int) { ++found; });
  EXPECT_EQ(found, 1);
}

}  // namespace
}  // namespace pss
