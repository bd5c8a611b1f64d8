#include "pss/volume/extract.hpp"

#include <algorithm>
#include <cmath>
#include <unordered_map>
#include <vector>

#include "pss/backend/cpu/parallel_for.hpp"

namespace pss {

ExtractLattice extraction_lattice(const VolumeScene& scene) {
  const Aabb box = scene.fields.volume.bounds();
  ExtractLattice l;
  l.origin = box.lo;
  l.spacing = scene.params.step;
  const vec3 n = glm::floor(box.extent() / l.spacing) + 1.0f;
  l.dims = ivec3(int(n.x), int(n.y), int(n.z));
  return l;
}

PointCloud extract_surface(const PreparedVolume& volume, Backend backend, Stats& stats, ExtractionCounts& counts) {
  const VolumeScene scene = volume.scene();
  const ExtractLattice lattice = extraction_lattice(scene);
  std::vector<ExtractedPoint> candidates(std::size_t(lattice.size()));
  counts.candidates = lattice.size();
  {
    ScopedPhase phase(stats, "projection");
    Progress progress("candidates", lattice.size());
    if (backend == Backend::cuda) {
      cuda::extract_candidates(scene, lattice, candidates, &progress);
    } else {
      cpu::parallel_for(lattice.size(), [&](std::int64_t i) { candidates[i] = extract_candidate(scene, lattice.at(i)); },
                        &progress);
    }
  }
  ScopedPhase phase(stats, "deduplicate");
  // One point per cell of side b: the one that moved least from its candidate.
  std::unordered_map<std::int64_t, std::size_t> best;
  const auto cell_of = [&](vec3 p) {
    const vec3 c = glm::floor((p - lattice.origin) / lattice.spacing) + 1.0f;  // +1: border points stay ≥ 0
    const std::int64_t nx = lattice.dims.x + 2, ny = lattice.dims.y + 2;
    return (std::int64_t(c.z) * ny + std::int64_t(c.y)) * nx + std::int64_t(c.x);
  };
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    if (!(candidates[i].moved < kInfinity)) continue;
    ++counts.accepted;
    const auto [it, inserted] = best.try_emplace(cell_of(candidates[i].point), i);
    if (!inserted && candidates[i].moved < candidates[it->second].moved) it->second = i;
  }
  // Cells in lattice order, so the output does not depend on hashing.
  std::vector<std::pair<std::int64_t, std::size_t>> kept(best.begin(), best.end());
  std::sort(kept.begin(), kept.end());
  PointCloud cloud;
  for (const auto& [cell, i] : kept) {
    cloud.positions.push_back(candidates[i].point);
    cloud.normals.push_back(candidates[i].normal);
  }
  counts.kept = std::int64_t(cloud.size());
  return cloud;
}

}  // namespace pss
