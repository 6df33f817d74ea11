#pragma once
// Bounding volume hierarchies for exact shadow rays (--visibility bvh, docs/shadows.md), built on
// the CPU in the layout of shared.h (BvhNode), and the compact nodes (BvhCompactNode) that the
// bottom levels are uploaded as for bvh.glsl. No GL here.

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

// Leaves hold at most this many primitives (a compact node's count has kBvhCompactCountBits).
inline constexpr int kBvhLeafSize = 8;
static_assert(kBvhLeafSize < (1 << gpu::kBvhCompactCountBits));
// From this depth on the builder halves lists at the median instead of at the SAH's best plane
// (which can peel a few primitives off at a time, level after level), so that a tree over up to
// kBvhMaxPrimitives, halved 23 more times into leaves of kBvhLeafSize, fits the traversal's
// stack of kBvhStackSize levels.
inline constexpr int kBvhMedianSplitDepth = 24;
inline constexpr int kBvhMaxPrimitives = kBvhLeafSize << 23;
static_assert(kBvhMedianSplitDepth + 23 < gpu::kBvhStackSize);

// Binned surface area heuristic (16 bins per axis over the primitives' centres), then halving at
// the median where the tree grows deep. An empty list gives one empty leaf; more than
// kBvhMaxPrimitives boxes throw std::length_error.
Bvh buildBvh(const std::vector<Bounds>& boxes);

// The grid a bottom level's compact nodes (shared.h, BvhCompactNode) give their boxes in, as
// BvhInstance::nodeGrid: the origin (xyz) a step below the root box, and the step (w), a 65532nd
// of the root box's largest side, so that every box rounded outwards by a step fits 16 bits.
glm::vec4 nodeGridFor(const Bounds& root);
// A node of a bottom level whose root box gave `grid`, compacted: its box rounded outwards to
// whole steps of the grid and grown by one step on each side, so that it holds the node's box
// however the traversal rounds; its first and count (within their bits, shared.h).
gpu::BvhCompactNode compactNode(const gpu::BvhNode& node, glm::vec4 grid);
int compactFirst(const gpu::BvhCompactNode& node);
int compactCount(const gpu::BvhCompactNode& node);
// The box a compact node stands for, in its object's coordinates.
Bounds compactBounds(const gpu::BvhCompactNode& node, glm::vec4 grid);

// A bottom level: the hierarchy over the triangles, and the triangles in the order of its leaves
// (leaf `first` indexes `triangles` directly).
struct TriangleBvh {
  std::vector<gpu::BvhNode> nodes;
  std::vector<gpu::BvhTriangle> triangles;
};
TriangleBvh buildTriangleBvh(const std::vector<glm::vec3>& positions,
                             const std::vector<glm::uvec3>& triangles);

}  // namespace penumbra
