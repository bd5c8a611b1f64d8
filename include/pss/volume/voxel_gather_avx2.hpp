// The voxel gather of N(x) (projection.hpp) eight voxels of a lattice row at a time, in AVX2:
// the CPU's hottest loop (docs/benchmarks.md). Compiled as a per-row scalar loop, each voxel
// took two or three branches that the data decide (in the ball? any weight? facing?); here a
// row's voxels are loaded in four 32-byte loads, tested in lanes, and the kept ones packed
// to the front of the lanes by one permutation and stored. The same voxels, in the same order
// and with the same window and θ as VoxelWeights computes them, up to rounding: d² and the
// window are computed with FMAs, so a voxel at |d| = ρ within rounding (window ~0) may be in
// or out, as in the scalar AVX2 copy (tests/volume_gather_test.cpp). CPU only: the GPU walks
// one voxel per step.
#pragma once

#include "pss/core/cpu_features.hpp"

#if PSS_CPU_AVX2
#include <immintrin.h>

#include <array>
#include <cstdint>

#include "pss/volume/fields.hpp"

namespace pss::detail {

// Four 32-byte loads of eight FeatureVoxels, transposed per 128-bit half, leave lane l
// holding voxel kLaneVoxel[l].
inline constexpr int kLaneVoxel[8] = {0, 2, 4, 6, 1, 3, 5, 7};

// For each 8-bit mask of kept lanes: those lanes in the voxels' order, four bits each, so
// that one permutation packs the kept voxels to the front in the lattice's order.
inline constexpr std::array<std::uint32_t, 256> kPackLanes = [] {
  std::array<std::uint32_t, 256> table{};
  for (int mask = 0; mask < 256; ++mask) {
    int slot = 0;
    for (int voxel = 0; voxel < 8; ++voxel)
      for (int lane = 0; lane < 8; ++lane)
        if (kLaneVoxel[lane] == voxel && (mask >> lane & 1)) table[mask] |= std::uint32_t(lane) << (4 * slot++);
  }
  return table;
}();

// Where the gathered voxels go: offsets from the ball's centre, window and θ (VoxelNeighbourhood),
// each array with room for 8 floats past `count`.
struct GatherSlots {
  float *dx, *dy, *dz, *window, *theta;
};

// Tests the voxels i, …, i + lanes − 1 (lanes ≤ 8) of one lattice row, the first at `index`,
// against the ball of squared radius r2 in the lattice's metric (dyz = the row's dy² + dz²
// there, metric_x the metric along x), computes their window
// (1 − d²/ρ²)² and θ as VoxelWeights does (with `weighted_only`, θ < 1e-5 leaves a voxel out),
// and stores those kept at `count`. Reads 8 voxels from `index`, whatever `lanes`: the caller
// keeps index + 8 within the array. Returns how many were kept.
[[gnu::target("avx2,fma,bmi2")]] inline int gather_row_avx2(const FeatureVoxel* features, std::int64_t index,
                                                            int i, int lanes, float origin_x, float spacing_x,
                                                            float center_x, float metric_x, float dy, float dz,
                                                            float dyz, float r2,
                                                            float inv_r2, vec3 n, bool weighted_only, int count,
                                                            const GatherSlots& out) {
  const float* voxels = &features[index].weight;
  const __m256 a = _mm256_loadu_ps(voxels), b = _mm256_loadu_ps(voxels + 8);
  const __m256 c = _mm256_loadu_ps(voxels + 16), d = _mm256_loadu_ps(voxels + 24);
  const __m256 t0 = _mm256_unpacklo_ps(a, b), t1 = _mm256_unpackhi_ps(a, b);
  const __m256 t2 = _mm256_unpacklo_ps(c, d), t3 = _mm256_unpackhi_ps(c, d);
  const __m256 weight = _mm256_shuffle_ps(t0, t2, _MM_SHUFFLE(1, 0, 1, 0));
  const __m256 gx = _mm256_shuffle_ps(t0, t2, _MM_SHUFFLE(3, 2, 3, 2));
  const __m256 gy = _mm256_shuffle_ps(t1, t3, _MM_SHUFFLE(1, 0, 1, 0));
  const __m256 gz = _mm256_shuffle_ps(t1, t3, _MM_SHUFFLE(3, 2, 3, 2));

  const __m256 voxel = _mm256_setr_ps(kLaneVoxel[0], kLaneVoxel[1], kLaneVoxel[2], kLaneVoxel[3], kLaneVoxel[4],
                                      kLaneVoxel[5], kLaneVoxel[6], kLaneVoxel[7]);
  const __m256 column = _mm256_add_ps(_mm256_set1_ps(float(i)), voxel);
  const __m256 dx = _mm256_sub_ps(_mm256_fmadd_ps(column, _mm256_set1_ps(spacing_x), _mm256_set1_ps(origin_x)),
                                  _mm256_set1_ps(center_x));
  const __m256 mx = _mm256_mul_ps(dx, _mm256_set1_ps(metric_x));
  const __m256 d2 = _mm256_fmadd_ps(mx, mx, _mm256_set1_ps(dyz));
  __m256 keep = _mm256_and_ps(_mm256_cmp_ps(d2, _mm256_set1_ps(r2), _CMP_LE_OQ),
                              _mm256_cmp_ps(voxel, _mm256_set1_ps(float(lanes)), _CMP_LT_OQ));

  const __m256 one = _mm256_set1_ps(1.0f);
  const __m256 u = _mm256_fnmadd_ps(d2, _mm256_set1_ps(inv_r2), one);
  const __m256 window = _mm256_mul_ps(u, u);
  // The facing test: clamp(2·⟨∇f/|∇f|, n⟩, 0, 1).
  __m256 facing = _mm256_mul_ps(gx, _mm256_set1_ps(n.x));
  facing = _mm256_fmadd_ps(gy, _mm256_set1_ps(n.y), facing);
  facing = _mm256_fmadd_ps(gz, _mm256_set1_ps(n.z), facing);
  facing = _mm256_min_ps(_mm256_max_ps(_mm256_add_ps(facing, facing), _mm256_setzero_ps()), one);
  const __m256 theta = _mm256_mul_ps(_mm256_mul_ps(window, weight), facing);
  if (weighted_only) keep = _mm256_and_ps(keep, _mm256_cmp_ps(theta, _mm256_set1_ps(1e-5f), _CMP_GE_OQ));

  const int mask = _mm256_movemask_ps(keep);
  const __m256i shifts = _mm256_setr_epi32(0, 4, 8, 12, 16, 20, 24, 28);
  const __m256i pack = _mm256_and_si256(_mm256_srlv_epi32(_mm256_set1_epi32(int(kPackLanes[mask])), shifts),
                                        _mm256_set1_epi32(7));
  _mm256_storeu_ps(out.dx + count, _mm256_permutevar8x32_ps(dx, pack));
  _mm256_storeu_ps(out.dy + count, _mm256_set1_ps(dy));
  _mm256_storeu_ps(out.dz + count, _mm256_set1_ps(dz));
  _mm256_storeu_ps(out.window + count, _mm256_permutevar8x32_ps(window, pack));
  _mm256_storeu_ps(out.theta + count, _mm256_permutevar8x32_ps(theta, pack));
  return __builtin_popcount(unsigned(mask));
}

}  // namespace pss::detail

#endif
