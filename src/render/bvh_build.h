#pragma once
// Bounding volume hierarchies for exact shadow rays (--visibility bvh, docs/shadows.md), built on
// the CPU as binary trees and stored in the layout of shared.h (BvhNode, BvhChild) that bvh.glsl
// traverses. No GL here.

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

// A hierarchy over boxes in shared.h's layout: `root`, and the inner nodes it leads to, each
// holding its two children; a leaf's primitives are primitives[first .. first + count), indices
// into the boxes it was built from. An empty list gives no nodes and a root of count 0 and empty
// bounds, which a traversal must not enter.
struct Bvh {
  gpu::BvhChild root{};
  std::vector<gpu::BvhNode> nodes;
  std::vector<std::uint32_t> primitives;
};

// What a child of shared.h's layout holds.
int bvhFirst(const gpu::BvhChild& child);
int bvhCount(const gpu::BvhChild& child);
inline bool bvhIsLeaf(const gpu::BvhChild& child) {
  return bvhCount(child) > 0;
}
Bounds bvhBounds(const gpu::BvhChild& child);
// `child` with `first` moved by `innerBase` (an inner node) or `leafBase` (a leaf): where a tree's
// indices land once its nodes and primitives are appended to longer buffers.
gpu::BvhChild bvhRebased(const gpu::BvhChild& child, int innerBase, int leafBase);

// Leaves hold at most this many primitives (unless the tree would grow deeper than the traversal's
// stack, kBvhStackSize).
inline constexpr int kBvhLeafSize = 8;

// Binned surface area heuristic (16 bins per axis over the primitives' centres).
Bvh buildBvh(const std::vector<Bounds>& boxes);

// A bottom level: the hierarchy over the triangles, and the triangles in the order of its leaves
// (leaf `first` indexes `triangles` directly).
struct TriangleBvh {
  gpu::BvhChild root{};
  std::vector<gpu::BvhNode> nodes;
  std::vector<gpu::BvhTriangle> triangles;
};
TriangleBvh buildTriangleBvh(const std::vector<glm::vec3>& positions,
                             const std::vector<glm::uvec3>& triangles);

}  // namespace penumbra
