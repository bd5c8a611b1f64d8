#include "pss/points/thinning.hpp"

#include "pss/spatial/support_grid.hpp"

namespace pss {

namespace {

// |z − g(x, y)| of p in the frame of `by`: how far p lies off by's graph.
float off_graph(const LocalPolynomial& by, vec3 p) {
  const vec3 l = by.frame().to_local(p);
  return abs(l.z - by.g(l.x, l.y));
}

}  // namespace

std::vector<LocalPolynomial> thin_local_polynomials(std::span<const LocalPolynomial> locals, float spacing,
                                                    float tolerance) {
  if (!(spacing > 0)) return {locals.begin(), locals.end()};
  std::vector<vec3> origins(locals.size());
  std::vector<float> reach(locals.size());
  for (std::size_t i = 0; i < locals.size(); ++i) {
    origins[i] = locals[i].origin;
    reach[i] = spacing * locals[i].radius;
  }
  // Sample k's support is its reach: the query at p_j finds every k within spacing·b_k.
  const SupportGrid grid(origins, reach, 1.0f);
  const SupportGridView view = grid.view();
  const std::span<const int> input_index = grid.original_index();
  std::vector<char> kept(locals.size(), 0);  // by input index
  std::vector<LocalPolynomial> out;
  // In input order, so that the result does not depend on the grid's.
  for (std::size_t j = 0; j < locals.size(); ++j) {
    bool represented = false;
    view.for_each_covering(locals[j].origin, [&](vec3, float, int s) {
      const int k = input_index[std::size_t(s)];
      if (represented || !kept[std::size_t(k)]) return;
      represented = off_graph(locals[std::size_t(k)], locals[j].origin) <= tolerance * locals[std::size_t(k)].radius;
    });
    if (represented) continue;
    kept[j] = 1;
    out.push_back(locals[j]);
  }
  return out;
}

}  // namespace pss
