// How a mesh's triangles meet (internal to src/mesh): its edges with the triangles on each,
// the components triangles make across edges, and the fans a vertex's corners make across
// the edges at it. What topology() counts and remove_pinches() repairs.
#pragma once

#include <array>
#include <cstdint>
#include <numeric>
#include <vector>

namespace pss::mesh_detail {

struct UnionFind {
  std::vector<std::int64_t> parent;
  explicit UnionFind(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), std::int64_t(0)); }
  std::int64_t find(std::int64_t i) {
    while (parent[std::size_t(i)] != i) i = parent[std::size_t(i)] = parent[std::size_t(parent[std::size_t(i)])];
    return i;
  }
  void join(std::int64_t a, std::int64_t b) {  // the least member labels the set
    a = find(a);
    b = find(b);
    if (a != b) parent[std::size_t(std::max(a, b))] = std::min(a, b);
  }
};

// One side of a triangle, the edge between `low` < `high`; `forward` when the triangle
// runs from low to high.
struct Side {
  int low, high;
  bool forward;
  std::int64_t triangle;
  bool same_edge(const Side& o) const { return low == o.low && high == o.high; }
};

struct Incidence {
  std::vector<Side> sides;  // sorted by edge, then triangle: an edge's sides are a run
  UnionFind components;     // of triangles
  UnionFind fans;           // of corners 3·triangle + k (vertex k of the triangle)
};

// Triangles with a repeated vertex take part in no fan (their corners stay alone).
Incidence incidence(const std::vector<std::array<int, 3>>& triangles);

}  // namespace pss::mesh_detail
