// Bounding volume hierarchy over the balls B(p_i, b): the acceleration structure that
// finds, for a ray, the nearest intersection with the local polynomials stored at the
// samples (paper §5.2, "Intersection"), where the paper rasterised one disc per ball.
//
// Flat arrays (nodes + primitive order), so the same traversal runs on the CPU and, after
// the arrays are uploaded, on the GPU: kernels see a BvhView (pointers and sizes, by
// value); traversal keeps a fixed-size stack and allocates nothing.
#pragma once

#include <span>
#include <vector>

#include "pss/core/types.hpp"

namespace pss {

// Internal nodes have count == 0 and their children at first and first + 1 (allocated in
// pairs); leaves hold primitives [first, first + count) of the BVH order.
struct BvhNode {
  vec3 lo;
  int first;
  vec3 hi;
  int count;
};

// Entry and exit distances of a ray through a box; empty when t_enter > t_exit. inv_dir
// may hold infinities (axis-parallel rays): the slab test stays correct for origins off
// the slab planes.
PSS_INLINE vec2 ray_box(vec3 origin, vec3 inv_dir, vec3 lo, vec3 hi) {
  const vec3 a = (lo - origin) * inv_dir, b = (hi - origin) * inv_dir;
  const vec3 near = glm::min(a, b), far = glm::max(a, b);
  // Plain comparisons: pss::min/max are fminf/fmaxf, library calls on the CPU.
  const float enter = near.x > near.y ? near.x : near.y, exit = far.x < far.y ? far.x : far.y;
  return vec2(enter > near.z ? enter : near.z, exit < far.z ? exit : far.z);
}

// Entry and exit of a ray (unit direction) through the ball B(center, radius); false when
// it misses.
PSS_INLINE bool ray_ball(const Ray& ray, vec3 center, float radius, float& t_enter, float& t_exit) {
  const vec3 oc = ray.origin - center;
  const float b = glm::dot(oc, ray.dir);
  // c − b² as |oc − b·d|², the distance of the centre from the line: no cancellation for
  // far origins.
  const float line2 = length2(oc - b * ray.dir);
  const float disc = radius * radius - line2;
  if (disc < 0) return false;
  const float s = sqrt(disc);
  t_enter = -b - s;
  t_exit = -b + s;
  return true;
}

struct BvhView {
  const BvhNode* nodes = nullptr;
  const int* primitives = nullptr;  // BVH order → input index
  int node_count = 0;
  int primitive_count = 0;

  static constexpr int kStackSize = 64;

  // Closest-hit traversal over [t_min, t_max]: calls leaf(k, t_max) for the primitive in
  // BVH order k of every leaf the ray reaches before the current t_max; leaf lowers t_max
  // (its reference) when it finds a nearer hit, which prunes the rest. Children are visited
  // near first.
  template <class Leaf>
  PSS_HOST_DEVICE void closest(const Ray& ray, float t_min, float& t_max, Leaf&& leaf) const {
    if (node_count == 0) return;
    const vec3 inv_dir = 1.0f / ray.dir;
    int stack[kStackSize];
    float stack_t[kStackSize];
    int top = 0;
    const vec2 root = ray_box(ray.origin, inv_dir, nodes[0].lo, nodes[0].hi);
    if (root.x > root.y || root.y < t_min || root.x > t_max) return;
    stack[top] = 0;
    stack_t[top++] = root.x;
    while (top > 0) {
      --top;
      if (stack_t[top] > t_max) continue;
      const BvhNode node = nodes[stack[top]];
      if (node.count > 0) {
        for (int k = node.first; k < node.first + node.count; ++k) leaf(k, t_max);
        continue;
      }
      const vec2 a = ray_box(ray.origin, inv_dir, nodes[node.first].lo, nodes[node.first].hi);
      const vec2 b = ray_box(ray.origin, inv_dir, nodes[node.first + 1].lo, nodes[node.first + 1].hi);
      const bool hit_a = a.x <= a.y && a.y >= t_min && a.x <= t_max;
      const bool hit_b = b.x <= b.y && b.y >= t_min && b.x <= t_max;
      // Depth ≤ log2(n) + 1 for a median split, far below the stack size; the guard only
      // keeps a malformed tree from writing past it.
      if (top + 2 > kStackSize) break;
      if (hit_a && hit_b) {
        const bool a_first = a.x <= b.x;
        stack[top] = a_first ? node.first + 1 : node.first;
        stack_t[top++] = a_first ? b.x : a.x;
        stack[top] = a_first ? node.first : node.first + 1;
        stack_t[top++] = a_first ? a.x : b.x;
      } else if (hit_a) {
        stack[top] = node.first;
        stack_t[top++] = a.x;
      } else if (hit_b) {
        stack[top] = node.first + 1;
        stack_t[top++] = b.x;
      }
    }
  }
};

class Bvh {
 public:
  // Over arbitrary primitive boxes: median split of the box centres along the longest axis
  // of their bounds, O(n log n); nodes bound their primitives' boxes.
  explicit Bvh(std::span<const Aabb> boxes, int leaf_size = 4);
  // Over the equal balls B(centers[i], radius).
  Bvh(std::span<const vec3> centers, float radius, int leaf_size = 4);

  BvhView view() const;
  std::span<const BvhNode> nodes() const { return nodes_; }
  std::span<const int> primitives() const { return primitives_; }
  int depth() const { return depth_; }

 private:
  std::vector<BvhNode> nodes_;
  std::vector<int> primitives_;
  int depth_ = 0;
};

}  // namespace pss
