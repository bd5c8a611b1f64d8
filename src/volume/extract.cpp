#include "pss/volume/extract.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <unordered_map>
#include <vector>

#include "pss/backend/parallel_for.hpp"
#include "pss/core/error.hpp"

namespace pss {

ExtractLattice extraction_lattice(const VolumeScene& scene) {
  const Aabb box = scene.fields.volume.bounds();
  ExtractLattice l;
  l.origin = box.lo;
  l.spacing = scene.params.step;
  // Counted in double: a tiny b makes a lattice whose size overflows int, then int64.
  double n[3], total = 1;
  for (int a = 0; a < 3; ++a) {
    n[a] = std::floor(double(box.extent()[a]) / double(l.spacing)) + 1.0;
    total *= n[a];
  }
  if (!(total <= double(kMaxExtractCandidates))) {
    char message[300];
    std::snprintf(message, sizeof message,
                  "a step b = %g makes a %.0fx%.0fx%.0f lattice of %.4g candidates on this %gx%gx%g box, more than "
                  "the %lld (2^28) pss extract projects (7.5 GiB of candidates); use a larger b or h",
                  double(l.spacing), n[0], n[1], n[2], total, double(box.extent().x), double(box.extent().y),
                  double(box.extent().z), (long long)kMaxExtractCandidates);
    throw Error(message);
  }
  l.dims = ivec3(int(n[0]), int(n[1]), int(n[2]));
  return l;
}

PointCloud extract_surface(const PreparedVolume& volume, Backend backend, Stats& stats, ExtractionCounts& counts) {
  const ExtractLattice lattice = extraction_lattice(volume.scene());
  counts.candidates = lattice.size();
  std::vector<ExtractedPoint> candidates;
  {
    const SceneMirror mirror(backend, volume);
    Mirror<ExtractedPoint> out(backend, std::size_t(lattice.size()));
    Progress progress("candidates", lattice.size());
    parallel_for(backend, "projection", lattice.size(), ExtractCandidatesKernel{mirror.scene(), lattice, out.data()},
                 stats, &progress);
    candidates = out.take();
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
