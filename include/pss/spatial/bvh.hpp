// Bounding volume hierarchy over the balls B(p_i, b_i): the acceleration structure that
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

// A node of the 4-wide tree: its children's boxes side by side, one array per coordinate,
// so that one visit tests the four together (SIMD lanes on the CPU, one load on the GPU).
// Slot c holds an inner node (count[c] == 0, child[c] its index), a leaf (count[c] > 0,
// primitives [child[c], child[c] + count[c]) of the BVH order) or nothing (count[c] < 0).
struct BvhNode {
  static constexpr int kWidth = 4;
  float lo_x[kWidth], lo_y[kWidth], lo_z[kWidth];
  float hi_x[kWidth], hi_y[kWidth], hi_z[kWidth];
  int child[kWidth];
  int count[kWidth];
};

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
  const BvhNode* nodes = nullptr;  // nodes[0] is the root
  const int* primitives = nullptr;  // BVH order → input index
  int node_count = 0;
  int primitive_count = 0;

  // A visit pushes at most 3 entries more than it pops, and the tree is at most 24 levels
  // deep (Bvh's build): 3·24 + 1 entries.
  static constexpr int kStackSize = 73;
  // An entry is a child slot c of node k, k·4 + c: 4 bytes where the slot's range and entry
  // distance took 12. The stack was most of a GPU thread's stack, which lives in local
  // memory (tests/gpu/kernel_stacks.py); the slot's box is tested again when popped.
  static constexpr int kMaxNodes = 1 << 30;

  // Entry and exit of the ray through the box of slot c of `node`. Boxes are slab-tested with
  // inv_dir, which may hold infinities (axis-parallel rays): the test stays correct for
  // origins off the slab planes. Plain comparisons: pss::min/max are fminf/fmaxf, library
  // calls on the CPU.
  PSS_HOST_DEVICE static void slot_span(const BvhNode& node, int c, vec3 o, vec3 inv_dir, float& enter, float& exit) {
    const float ax = (node.lo_x[c] - o.x) * inv_dir.x, bx = (node.hi_x[c] - o.x) * inv_dir.x;
    const float ay = (node.lo_y[c] - o.y) * inv_dir.y, by = (node.hi_y[c] - o.y) * inv_dir.y;
    const float az = (node.lo_z[c] - o.z) * inv_dir.z, bz = (node.hi_z[c] - o.z) * inv_dir.z;
    const float nx = ax < bx ? ax : bx, ny = ay < by ? ay : by, nz = az < bz ? az : bz;
    const float fx = ax < bx ? bx : ax, fy = ay < by ? by : ay, fz = az < bz ? bz : az;
    const float nxy = nx > ny ? nx : ny, fxy = fx < fy ? fx : fy;
    enter = nxy > nz ? nxy : nz;
    exit = fxy < fz ? fxy : fz;
  }

  // Closest-hit traversal over [t_min, t_max]: calls leaf(k, t_max) for the primitive in
  // BVH order k of every leaf the ray reaches before the current t_max; leaf lowers t_max
  // (its reference) when it finds a nearer hit, which prunes the rest. Children are visited
  // near first.
  template <class Leaf>
  PSS_HOST_DEVICE void closest(const Ray& ray, float t_min, float& t_max, Leaf&& leaf) const {
    if (node_count == 0) return;
    const vec3 inv_dir = 1.0f / ray.dir;
    const vec3 o = ray.origin;
    unsigned stack[kStackSize];
    int top = 0;
    // Pushes the slots of node k that the ray meets in [t_min, t_max], far to near so that
    // the nearest is visited next (insertion into a list sorted by falling entry); false
    // when they do not fit, which the build's depth bound rules out: the guard only keeps
    // a malformed tree from writing past the stack.
    const auto push_children = [&](int k) {
      const BvhNode& node = nodes[k];
      float enter[BvhNode::kWidth];
      unsigned slot[BvhNode::kWidth];
      int n = 0;
      for (int c = 0; c < BvhNode::kWidth; ++c) {
        float in, out;
        slot_span(node, c, o, inv_dir, in, out);
        if (node.count[c] < 0 || !(in <= out && out >= t_min && in <= t_max)) continue;
        int i = n++;
        for (; i > 0 && enter[i - 1] < in; --i) {
          enter[i] = enter[i - 1];
          slot[i] = slot[i - 1];
        }
        enter[i] = in;
        slot[i] = unsigned(k) * BvhNode::kWidth + unsigned(c);
      }
      if (top + n > kStackSize) return false;
      for (int i = 0; i < n; ++i) stack[top++] = slot[i];
      return true;
    };
    if (!push_children(0)) return;
    while (top > 0) {
      const unsigned s = stack[--top];
      const BvhNode& node = nodes[s / BvhNode::kWidth];
      const int c = int(s % BvhNode::kWidth);
      float in, out;
      slot_span(node, c, o, inv_dir, in, out);
      if (in > t_max) continue;  // a nearer hit was found since the push
      if (node.count[c] > 0) {
        for (int k = node.child[c]; k < node.child[c] + node.count[c]; ++k) leaf(k, t_max);
        continue;
      }
      if (!push_children(node.child[c])) break;
    }
  }
};

class Bvh {
 public:
  // Over arbitrary primitive boxes: a binary tree by binned surface-area-heuristic splits of
  // the box centres (median splits along the longest axis where no bin boundary separates
  // them, and below depth 20), O(n log n), then collapsed into the 4-wide tree (each node
  // takes its children's children); boxes bound their primitives' boxes.
  explicit Bvh(std::span<const Aabb> boxes, int leaf_size = 4);
  // Over the equal balls B(centers[i], radius).
  Bvh(std::span<const vec3> centers, float radius, int leaf_size = 4);

  BvhView view() const;
  std::span<const BvhNode> nodes() const { return nodes_; }
  std::span<const int> primitives() const { return primitives_; }
  int depth() const { return depth_; }  // levels of the 4-wide tree

 private:
  std::vector<BvhNode> nodes_;
  std::vector<int> primitives_;
  int depth_ = 0;
};

}  // namespace pss
