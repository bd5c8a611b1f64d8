#include "pss/mesh/mesh_cloud.hpp"

#include <algorithm>
#include <vector>

#include <glm/geometric.hpp>

#include "pss/core/connected_components.hpp"

namespace pss {

std::int64_t remove_unsupported_parts(TriangleMesh& mesh, const CountSamples& count) {
  const std::size_t nv = mesh.positions.size();
  std::vector<int> part(nv, -1);  // each vertex's part, numbered densely
  int parts = 0;
  {
    ConnectedComponents<int> joined(nv);
    for (const auto& t : mesh.triangles) {
      joined.join(t[0], t[1]);
      joined.join(t[0], t[2]);
    }
    std::vector<int> of_root(nv, -1);
    for (std::size_t v = 0; v < nv; ++v) {
      int& id = of_root[std::size_t(joined.find(int(v)))];
      if (id < 0) id = parts++;
      part[v] = id;
    }
  }
  std::vector<glm::dvec3> centre(std::size_t(parts), glm::dvec3(0.0));
  std::vector<double> members(std::size_t(parts), 0.0), radius(std::size_t(parts), 0.0);
  for (std::size_t v = 0; v < nv; ++v) {
    centre[std::size_t(part[v])] += glm::dvec3(mesh.positions[v]);
    members[std::size_t(part[v])] += 1;
  }
  for (int p = 0; p < parts; ++p) centre[std::size_t(p)] /= members[std::size_t(p)];
  for (std::size_t v = 0; v < nv; ++v) {
    const auto p = std::size_t(part[v]);
    radius[p] = std::max(radius[p], glm::length(glm::dvec3(mesh.positions[v]) - centre[p]));
  }
  std::vector<vec3> at(static_cast<std::size_t>(parts));
  std::vector<float> within(static_cast<std::size_t>(parts));
  for (std::size_t p = 0; p < std::size_t(parts); ++p) {
    at[p] = vec3(centre[p]);
    within[p] = float(radius[p]);
  }
  std::vector<int> inside(std::size_t(parts), 0);
  count(at, within, inside);
  std::vector<char> held(std::size_t(parts), 0);
  for (std::size_t p = 0; p < std::size_t(parts); ++p) held[p] = inside[p] >= kMinPartSamples;
  const auto removed = std::int64_t(std::count(held.begin(), held.end(), char(0)));
  if (removed == 0) return 0;
  std::erase_if(mesh.triangles, [&](const std::array<int, 3>& t) { return !held[std::size_t(part[std::size_t(t[0])])]; });
  drop_unused_vertices(mesh);
  return removed;
}

}  // namespace pss
