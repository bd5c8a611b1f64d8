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

float half_area(const Aabb& b) {
  const vec3 e = b.extent();
  return e.x * e.y + e.y * e.z + e.z * e.x;
}

// The split of primitives [begin, end) that the surface area heuristic prefers among 16
// bins of the centres along each axis: the least Σ area(child)·count(child), so that a ray
// meets as few boxes and primitives as the boxes' overlap allows (the balls overlap ~16-fold
// and their discs lie on one surface, where a median split cuts through dense sheets).
// Returns the axis and the bin boundary, or axis −1 when every centre falls in one bin.
struct Split {
  int axis = -1;
  float position = 0;
};
Split sah_split(std::span<const Aabb> boxes, std::span<const vec3> centers, std::span<const int> order,
                const Aabb& center_bounds) {
  constexpr int kBins = 16;
  Split best;
  float best_cost = kInfinity;
  for (int axis = 0; axis < 3; ++axis) {
    const float lo = center_bounds.lo[axis], extent = center_bounds.hi[axis] - lo;
    if (!(extent > 0)) continue;
    const float scale = kBins / extent;
    Aabb bin_box[kBins];
    int bin_count[kBins] = {};
    for (int i : order) {
      const int b = std::min(kBins - 1, int((centers[i][axis] - lo) * scale));
      bin_box[b].grow(boxes[i]);
      ++bin_count[b];
    }
    // Costs of the kBins − 1 boundaries, from the right, then swept from the left.
    float right_cost[kBins];
    Aabb right;
    int right_count = 0;
    for (int b = kBins - 1; b > 0; --b) {
      right.grow(bin_box[b]);
      right_count += bin_count[b];
      right_cost[b] = right_count > 0 ? half_area(right) * float(right_count) : 0;
    }
    Aabb left;
    int left_count = 0;
    for (int b = 0; b < kBins - 1; ++b) {
      left.grow(bin_box[b]);
      left_count += bin_count[b];
      if (left_count == 0 || left_count == int(order.size())) continue;
      const float cost = half_area(left) * float(left_count) + right_cost[b + 1];
      if (cost < best_cost) {
        best_cost = cost;
        best.axis = axis;
        best.position = lo + float(b + 1) / scale;
      }
    }
  }
  return best;
}

// The binary tree the build makes first: inner nodes have count == 0 and their children at
// first and first + 1; leaves hold primitives [first, first + count) of the BVH order.
struct BinaryNode {
  Aabb box;
  int first = 0, count = 0;
};

// Below this depth of the binary tree only median splits, whose depth is log2 of the count:
// skewed samplings cannot push the 4-wide tree past the traversal stack (BvhView::kStackSize).
constexpr int kSahDepth = 20;

std::vector<BinaryNode> build_binary(std::span<const Aabb> boxes, std::vector<int>& primitives, int leaf_size) {
  std::vector<vec3> centers(boxes.size());
  for (std::size_t i = 0; i < boxes.size(); ++i) centers[i] = boxes[i].center();
  std::vector<BinaryNode> nodes(1);
  nodes.reserve(2 * (boxes.size() / std::size_t(leaf_size) + 1));
  struct Task {
    int node, begin, end, depth;
  };
  std::vector<Task> tasks{{0, 0, int(boxes.size()), 1}};
  while (!tasks.empty()) {
    const Task task = tasks.back();
    tasks.pop_back();
    Aabb bounds, center_bounds;
    for (int i = task.begin; i < task.end; ++i) {
      bounds.grow(boxes[primitives[i]]);
      center_bounds.grow(centers[primitives[i]]);
    }
    nodes[task.node].box = bounds;
    const int count = task.end - task.begin;
    const vec3 extent = center_bounds.extent();
    if (count <= leaf_size || std::max({extent.x, extent.y, extent.z}) == 0) {
      nodes[task.node].first = task.begin;
      nodes[task.node].count = count;
      continue;
    }
    const auto first = primitives.begin() + task.begin, last = primitives.begin() + task.end;
    const Split split = task.depth < kSahDepth
                            ? sah_split(boxes, centers, std::span<const int>(&*first, std::size_t(count)), center_bounds)
                            : Split{};
    int mid = split.axis < 0 ? task.begin
                             : int(std::partition(first, last, [&](int i) { return centers[i][split.axis] < split.position; }) -
                                   primitives.begin());
    if (mid == task.begin || mid == task.end) {  // no bin boundary separates them
      const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
      mid = task.begin + count / 2;
      std::nth_element(first, primitives.begin() + mid, last,
                       [&](int a, int b) { return centers[a][axis] < centers[b][axis]; });
    }
    const int left = int(nodes.size());
    nodes.emplace_back();
    nodes.emplace_back();
    nodes[task.node].first = left;
    nodes[task.node].count = 0;
    tasks.push_back({left, task.begin, mid, task.depth + 1});
    tasks.push_back({left + 1, mid, task.end, task.depth + 1});
  }
  return nodes;
}

// The 4-wide node of binary node b (made at index `at`): b's children's children, or a
// child itself where it is a leaf. Returns the depth of the 4-wide subtree.
int collapse(const std::vector<BinaryNode>& binary, int b, std::vector<BvhNode>& nodes, int at) {
  int slots[BvhNode::kWidth], n = 0;
  if (binary[b].count > 0) {
    slots[n++] = b;  // the whole tree is one leaf
  } else {
    for (int c : {binary[b].first, binary[b].first + 1}) {
      if (binary[c].count > 0) {
        slots[n++] = c;
      } else {
        slots[n++] = binary[c].first;
        slots[n++] = binary[c].first + 1;
      }
    }
  }
  BvhNode node;
  int depth = 1;
  for (int k = 0; k < BvhNode::kWidth; ++k) {
    const Aabb box = k < n ? binary[slots[k]].box : Aabb{};
    node.lo_x[k] = box.lo.x;
    node.lo_y[k] = box.lo.y;
    node.lo_z[k] = box.lo.z;
    node.hi_x[k] = box.hi.x;
    node.hi_y[k] = box.hi.y;
    node.hi_z[k] = box.hi.z;
    node.count[k] = k < n ? binary[slots[k]].count : -1;
    node.child[k] = k < n && binary[slots[k]].count > 0 ? binary[slots[k]].first : 0;
  }
  nodes[at] = node;
  for (int k = 0; k < n; ++k) {
    if (binary[slots[k]].count > 0) continue;
    const int index = int(nodes.size());
    nodes.emplace_back();
    nodes[at].child[k] = index;
    depth = std::max(depth, 1 + collapse(binary, slots[k], nodes, index));
  }
  return depth;
}

}  // namespace

Bvh::Bvh(std::span<const vec3> centers, float radius, int leaf_size) : Bvh(ball_boxes(centers, radius), leaf_size) {}

Bvh::Bvh(std::span<const Aabb> boxes, int leaf_size) {
  if (leaf_size < 1) throw Error("BVH leaf size must be at least 1");
  primitives_.resize(boxes.size());
  std::iota(primitives_.begin(), primitives_.end(), 0);
  if (boxes.empty()) return;
  const std::vector<BinaryNode> binary = build_binary(boxes, primitives_, leaf_size);
  nodes_.reserve(binary.size() / 2 + 1);
  nodes_.emplace_back();
  depth_ = collapse(binary, 0, nodes_, 0);
  if (3 * depth_ + 1 > BvhView::kStackSize) throw Error("BVH too deep for the traversal stack");
  if (nodes_.size() > std::size_t(BvhView::kMaxNodes)) throw Error("BVH has too many nodes for the traversal stack");
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
