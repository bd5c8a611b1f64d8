#include "pss/spatial/bvh.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "pss/core/error.hpp"

namespace pss {

namespace {

std::vector<Aabb> ball_boxes(std::span<const vec3> centers, float radius) {
  if (!(radius > 0) || !std::isfinite(radius)) throw Error("BVH ball radius must be a positive number");
  std::vector<Aabb> boxes(centers.size());
  for (std::size_t i = 0; i < centers.size(); ++i) {
    boxes[i].lo = centers[i] - vec3(radius);
    boxes[i].hi = centers[i] + vec3(radius);
  }
  return boxes;
}

}  // namespace

Bvh::Bvh(std::span<const vec3> centers, float radius, int leaf_size) : Bvh(ball_boxes(centers, radius), leaf_size) {}

Bvh::Bvh(std::span<const Aabb> boxes, int leaf_size) {
  if (leaf_size < 1) throw Error("BVH leaf size must be at least 1");
  primitives_.resize(boxes.size());
  std::iota(primitives_.begin(), primitives_.end(), 0);
  if (boxes.empty()) return;
  std::vector<vec3> centers(boxes.size());
  for (std::size_t i = 0; i < boxes.size(); ++i) centers[i] = boxes[i].center();
  nodes_.reserve(2 * (boxes.size() / std::size_t(leaf_size) + 1));
  nodes_.push_back({});

  struct Task {
    int node, begin, end, depth;
  };
  std::vector<Task> tasks{{0, 0, int(boxes.size()), 1}};
  while (!tasks.empty()) {
    const Task task = tasks.back();
    tasks.pop_back();
    depth_ = std::max(depth_, task.depth);
    Aabb bounds, center_bounds;
    for (int i = task.begin; i < task.end; ++i) {
      bounds.grow(boxes[primitives_[i]]);
      center_bounds.grow(centers[primitives_[i]]);
    }
    nodes_[task.node].lo = bounds.lo;
    nodes_[task.node].hi = bounds.hi;
    const int count = task.end - task.begin;
    const vec3 extent = center_bounds.extent();
    if (count <= leaf_size || std::max({extent.x, extent.y, extent.z}) == 0) {
      nodes_[task.node].first = task.begin;
      nodes_[task.node].count = count;
      continue;
    }
    const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
    const int mid = task.begin + count / 2;
    std::nth_element(primitives_.begin() + task.begin, primitives_.begin() + mid, primitives_.begin() + task.end,
                     [&](int a, int b) { return centers[a][axis] < centers[b][axis]; });
    const int left = int(nodes_.size());
    nodes_.push_back({});
    nodes_.push_back({});
    nodes_[task.node].first = left;
    nodes_[task.node].count = 0;
    tasks.push_back({left, task.begin, mid, task.depth + 1});
    tasks.push_back({left + 1, mid, task.end, task.depth + 1});
  }
  if (depth_ > BvhView::kStackSize) throw Error("BVH too deep for the traversal stack");
}

BvhView Bvh::view() const {
  BvhView v;
  v.nodes = nodes_.data();
  v.primitives = primitives_.data();
  v.node_count = int(nodes_.size());
  v.primitive_count = int(primitives_.size());
  return v;
}

}  // namespace pss
