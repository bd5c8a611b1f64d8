// `pss extract`: the PSS of a volume as an oriented point set, independent of any view
// (issue 4; the paper's Figure 5 flow renders such a set with `pss render`). Candidates on
// a lattice of spacing b that pass the fragment test are projected (predictor-corrector)
// until they settle within ε; the accepted points are thinned to about one per b-cell.
#pragma once

#include <cstdint>
#include <span>

#include "pss/backend/backend.hpp"
#include "pss/core/progress.hpp"
#include "pss/points/cloud.hpp"
#include "pss/volume/prepared.hpp"

namespace pss {

struct ExtractedPoint {
  vec3 point{0.0f};
  vec3 normal{0.0f};
  float moved = kInfinity;  // |γ − candidate|; infinity when rejected
};

// The lattice: candidate i of dims n is at the box's low corner + (i, j, k)·b.
struct ExtractLattice {
  vec3 origin{0.0f};
  ivec3 dims{0};
  float spacing = 1;

  PSS_HOST_DEVICE vec3 at(std::int64_t i) const {
    const int x = int(i % dims.x), y = int(i / dims.x % dims.y), z = int(i / (std::int64_t(dims.x) * dims.y));
    return origin + spacing * vec3(float(x), float(y), float(z));
  }
  PSS_HOST_DEVICE std::int64_t size() const { return std::int64_t(dims.x) * dims.y * dims.z; }
};

// The most candidates extraction projects: 2^28. Each costs a 28-byte ExtractedPoint
// (7.5 GiB at the cap) and a projection; a surface sampled once per b needs far fewer.
inline constexpr std::int64_t kMaxExtractCandidates = std::int64_t(1) << 28;

// The candidate lattice, box / b + 1 per axis; throws Error above kMaxExtractCandidates.
ExtractLattice extraction_lattice(const VolumeScene& scene);

// One candidate: skipped unless its brick is occupied and it passes the fragment test;
// accepted when repeated projection settles within ε before leaving the ball B(r, b), where
// the data have a surface (surface_cells.hpp).
PSS_INLINE ExtractedPoint extract_candidate(const VolumeScene& s, vec3 r) {
  ExtractedPoint out;
  const BrickView& bricks = s.bricks;
  if (!bricks.is_occupied(bricks.brick_of(s.fields.volume.to_grid(r)))) return out;
  if (!passes_feature_test(s.fields, s.cells, s.feature, r, s.params.step)) return out;
  const VolumeParams& p = s.params;
  vec3 x = r;
  VoxelScratch nb;
  for (int attempt = 0; attempt <= p.max_retries; ++attempt) {
    const VolumeProjection proj = project_volume_point(s.fields, p, x, nb);
    if (proj.status != VolumeProjectionStatus::ok || length2(proj.point - r) > p.step * p.step) return out;
    if (length2(proj.point - x) <= p.epsilon * p.epsilon) {
      if (!is_data_surface(s.fields, s.cells, s.feature, proj.point, proj.normal, p.surface_reach())) return out;
      out.point = proj.point;
      out.normal = proj.normal;
      out.moved = glm::length(proj.point - r);
      return out;
    }
    x = proj.point;
  }
  return out;
}

// out[i] = the candidate at lattice point i (backend/parallel_for.hpp).
struct ExtractCandidatesKernel {
  VolumeScene scene;
  ExtractLattice lattice;
  ExtractedPoint* out;
  PSS_HOST_DEVICE void operator()(std::int64_t i) const { out[i] = extract_candidate(scene, lattice.at(i)); }
};

struct ExtractionCounts {
  std::int64_t candidates = 0, accepted = 0, kept = 0;
};

// Projects every candidate (on the backend), then keeps, per cell of side b, the accepted
// point whose candidate moved least. Normals point along ∇f.
PointCloud extract_surface(const PreparedVolume& volume, Backend backend, Stats& stats, ExtractionCounts& counts);

}  // namespace pss
