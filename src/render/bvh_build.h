#pragma once
// Bounding volume hierarchies for exact shadow rays (--visibility bvh, docs/shadows.md), built on
// the CPU in the layout of shared.h (BvhNode) that bvh.glsl traverses. No GL here.

#include <cstdint>
#include <limits>
#include <vector>

#include <glm/glm.hpp>

#include "shared.h"

namespace penumbra {

struct Bounds {
  glm::vec3 min{std::numeric_limits<float>::infinity()};
  glm::vec3 max{-std::numeric_limits<float>::infinity()};

  void grow(glm::vec3 point);
  void grow(const Bounds& other);
  bool empty() const { return !(min.x <= max.x); }
  glm::vec3 centre() const { return 0.5f * (min + max); }
  // Half the surface area (0 when empty): the SAH's measure of how often a ray meets the box.
  float halfArea() const;
  bool contains(const Bounds& other) const;
};

// The box around `bounds` moved by the affine transform `transform`.
Bounds transformed(const Bounds& bounds, const glm::mat4& transform);

// A hierarchy over boxes: nodes[0] is the root; a leaf's primitives are
// primitives[first .. first + count), indices into the boxes it was built from.
struct Bvh {
  std::vector<gpu::BvhNode> nodes;
  std::vector<std::uint32_t> primitives;
};

// What a node of shared.h's layout holds.
int bvhFirst(const gpu::BvhNode& node);
int bvhCount(const gpu::BvhNode& node);
inline bool bvhIsLeaf(const gpu::BvhNode& node) {
  return bvhCount(node) > 0;
}
Bounds bvhBounds(const gpu::BvhNode& node);

// Leaves hold at most this many primitives (unless the tree would grow deeper than the traversal's
// stack, kBvhStackSize).
inline constexpr int kBvhLeafSize = 8;

// Binned surface area heuristic (16 bins per axis over the primitives' centres). An empty list
// gives one empty leaf.
Bvh buildBvh(const std::vector<Bounds>& boxes);

// A bottom level: the hierarchy over the triangles, and the triangles in the order of its leaves
// (leaf `first` indexes `triangles` directly).
struct TriangleBvh {
  std::vector<gpu::BvhNode> nodes;
  std::vector<gpu::BvhTriangle> triangles;
};
TriangleBvh buildTriangleBvh(const std::vector<glm::vec3>& positions,
                             const std::vector<glm::uvec3>& triangles);

}  // namespace penumbra
