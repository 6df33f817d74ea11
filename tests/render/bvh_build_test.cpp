// The BVH builder of exact visibility (src/render/bvh_build.h): the tree's structure, and a CPU
// walk of its nodes (bvh.glsl walks them as compact nodes, which these tests check hold the same
// boxes) against testing every triangle.

#include "render/bvh_build.h"

#include <algorithm>
#include <random>
#include <vector>

#include <gtest/gtest.h>

namespace penumbra {
namespace {

struct TriangleSoup {
  std::vector<glm::vec3> positions;
  std::vector<glm::uvec3> triangles;
};

// Small triangles scattered in a unit cube, plus a few long thin ones across it (what SAH
// splits badly), so that leaves overlap.
TriangleSoup randomTriangles(int count, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::uniform_real_distribution<float> small(-0.05f, 0.05f);
  TriangleSoup soup;
  for (int i = 0; i < count; ++i) {
    const glm::vec3 centre(unit(random), unit(random), unit(random));
    const float stretch = i % 50 == 0 ? 10.0f : 1.0f;
    for (int corner = 0; corner < 3; ++corner) {
      soup.positions.push_back(centre +
                               stretch * glm::vec3(small(random), small(random), small(random)));
    }
    const auto first = static_cast<unsigned>(3 * i);
    soup.triangles.emplace_back(first, first + 1, first + 2);
  }
  return soup;
}

// Two-sided Moller-Trumbore, as bvh.glsl's rayMeetsTriangle.
bool rayMeetsTriangle(glm::vec3 origin, glm::vec3 direction, float tFar,
                      const gpu::BvhTriangle& triangle) {
  const glm::vec3 edge1(triangle.edge1);
  const glm::vec3 edge2(triangle.edge2);
  const glm::vec3 p = glm::cross(direction, edge2);
  const float determinant = glm::dot(edge1, p);
  if (determinant == 0.0f)
    return false;
  const float inverse = 1.0f / determinant;
  const glm::vec3 fromCorner = origin - glm::vec3(triangle.corner);
  const float u = glm::dot(fromCorner, p) * inverse;
  if (u < 0.0f || u > 1.0f)
    return false;
  const glm::vec3 q = glm::cross(fromCorner, edge1);
  const float v = glm::dot(direction, q) * inverse;
  if (v < 0.0f || u + v > 1.0f)
    return false;
  const float t = glm::dot(edge2, q) * inverse;
  return t > 0.0f && t < tFar;
}

bool rayMeetsBox(glm::vec3 origin, glm::vec3 direction, float tFar, const Bounds& box) {
  float enter = 0.0f;
  float leave = tFar;
  for (int axis = 0; axis < 3; ++axis) {
    const float inverse = 1.0f / direction[axis];
    float near = (box.min[axis] - origin[axis]) * inverse;
    float far = (box.max[axis] - origin[axis]) * inverse;
    if (near > far)
      std::swap(near, far);
    enter = std::max(enter, near);
    leave = std::min(leave, far);
  }
  return enter <= leave;
}

// A stack walk of the layout: children at first and first + 1, leaves index the triangles.
bool bvhBlocked(const TriangleBvh& bvh, glm::vec3 origin, glm::vec3 direction, float tFar) {
  std::vector<int> stack{0};
  while (!stack.empty()) {
    const gpu::BvhNode& node = bvh.nodes[static_cast<std::size_t>(stack.back())];
    stack.pop_back();
    if (!rayMeetsBox(origin, direction, tFar, bvhBounds(node)))
      continue;
    const int first = bvhFirst(node);
    if (!bvhIsLeaf(node)) {
      stack.push_back(first);
      stack.push_back(first + 1);
      continue;
    }
    for (int i = first; i < first + bvhCount(node); ++i)
      if (rayMeetsTriangle(origin, direction, tFar, bvh.triangles[static_cast<std::size_t>(i)]))
        return true;
  }
  return false;
}

bool bruteForceBlocked(const std::vector<gpu::BvhTriangle>& triangles, glm::vec3 origin,
                       glm::vec3 direction, float tFar) {
  for (const gpu::BvhTriangle& triangle : triangles)
    if (rayMeetsTriangle(origin, direction, tFar, triangle))
      return true;
  return false;
}

// Walks the tree from the root: the deepest node, the nodes reached, and how many leaves reach
// each triangle.
struct Walk {
  std::vector<int> timesInALeaf;
  int deepest = 0;
  std::size_t nodesReached = 0;
};

void visit(const TriangleBvh& bvh, int node, int depth, Walk& walk) {
  walk.deepest = std::max(walk.deepest, depth);
  ++walk.nodesReached;
  const gpu::BvhNode& current = bvh.nodes[static_cast<std::size_t>(node)];
  const int first = bvhFirst(current);
  if (bvhIsLeaf(current)) {
    for (int i = first; i < first + bvhCount(current); ++i) {
      ++walk.timesInALeaf[static_cast<std::size_t>(i)];
      const gpu::BvhTriangle& triangle = bvh.triangles[static_cast<std::size_t>(i)];
      Bounds box;
      box.grow(glm::vec3(triangle.corner));
      box.grow(glm::vec3(triangle.corner + triangle.edge1));
      box.grow(glm::vec3(triangle.corner + triangle.edge2));
      EXPECT_TRUE(bvhBounds(current).contains(box)) << "leaf " << node << ", triangle " << i;
    }
    return;
  }
  for (int child = first; child < first + 2; ++child) {
    EXPECT_TRUE(bvhBounds(current).contains(bvhBounds(bvh.nodes[static_cast<std::size_t>(child)])))
        << "node " << node << ", child " << child;
    visit(bvh, child, depth + 1, walk);
  }
}

TEST(BvhBuild, EveryTriangleIsInExactlyOneLeafInsideEveryBoxAboveIt) {
  const TriangleSoup soup = randomTriangles(3000, 1);
  const TriangleBvh bvh = buildTriangleBvh(soup.positions, soup.triangles);
  ASSERT_EQ(bvh.triangles.size(), soup.triangles.size());
  Walk walk{std::vector<int>(bvh.triangles.size(), 0)};
  visit(bvh, 0, 0, walk);
  for (std::size_t i = 0; i < walk.timesInALeaf.size(); ++i)
    ASSERT_EQ(walk.timesInALeaf[i], 1) << "triangle " << i;
  // The traversal's stack holds one node per level.
  EXPECT_LT(walk.deepest, gpu::kBvhStackSize);
  // Every node is reached: none is left over from the build.
  EXPECT_EQ(walk.nodesReached, bvh.nodes.size());
}

TEST(BvhBuild, LeavesAreSmallUnlessTheCentresCoincide) {
  const TriangleSoup soup = randomTriangles(500, 2);
  const TriangleBvh bvh = buildTriangleBvh(soup.positions, soup.triangles);
  for (const gpu::BvhNode& node : bvh.nodes) {
    if (bvhIsLeaf(node)) {
      EXPECT_LE(bvhCount(node), kBvhLeafSize);
    }
  }

  // The same triangle 20 times: no plane separates the centres, the list is halved instead.
  TriangleSoup same;
  same.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  same.triangles.assign(20, glm::uvec3(0, 1, 2));
  const TriangleBvh halved = buildTriangleBvh(same.positions, same.triangles);
  Walk walk{std::vector<int>(20, 0)};
  visit(halved, 0, 0, walk);
  EXPECT_EQ(walk.timesInALeaf, std::vector<int>(20, 1));
  EXPECT_GT(halved.nodes.size(), 1u);
}

// Triangles that halve in size and distance from the origin, one after the other: each level of
// the SAH's bins can split off only the few largest, so without halving at the median from
// kBvhMedianSplitDepth on these 120 would reach 32 levels.
TEST(BvhBuild, DeepTreesAreHalvedAtTheMedian) {
  TriangleSoup soup;
  float x = 1.0f;
  for (unsigned i = 0; i < 120; ++i, x *= 0.5f) {
    soup.positions.insert(soup.positions.end(),
                          {{x, 0.0f, 0.0f}, {x * 1.5f, x, 0.0f}, {x, 0.0f, x}});
    soup.triangles.emplace_back(3 * i, 3 * i + 1, 3 * i + 2);
  }
  const TriangleBvh bvh = buildTriangleBvh(soup.positions, soup.triangles);
  Walk walk{std::vector<int>(soup.triangles.size(), 0)};
  visit(bvh, 0, 0, walk);
  EXPECT_EQ(walk.timesInALeaf, std::vector<int>(soup.triangles.size(), 1));
  // At most 120 primitives reach kBvhMedianSplitDepth; 4 halvings leave at most 8.
  EXPECT_LE(walk.deepest, kBvhMedianSplitDepth + 4);
  EXPECT_GT(walk.deepest, kBvhMedianSplitDepth) << "the SAH alone should have gone this deep";
  for (const gpu::BvhNode& node : bvh.nodes) {
    if (bvhIsLeaf(node)) {
      EXPECT_LE(bvhCount(node), kBvhLeafSize);
    }
  }
}

// The bottom levels' compact nodes (shared.h, BvhCompactNode): each holds its node's box with at
// least a step to spare on every side (the traversal's rounding is far below a step), within
// 16 bits, and keeps its first and count.
TEST(BvhBuild, CompactNodesHoldTheirBoxesWithAStepToSpare) {
  const TriangleSoup soup = randomTriangles(2000, 5);
  TriangleBvh bvh = buildTriangleBvh(soup.positions, soup.triangles);
  const glm::vec4 grid = nodeGridFor(bvhBounds(bvh.nodes[0]));
  EXPECT_GT(grid.w, 0.0f);
  for (const gpu::BvhNode& node : bvh.nodes) {
    const gpu::BvhCompactNode compact = compactNode(node, grid);
    EXPECT_EQ(compactFirst(compact), bvhFirst(node));
    EXPECT_EQ(compactCount(compact), bvhCount(node));
    const Bounds box = bvhBounds(node);
    const Bounds held = compactBounds(compact, grid);
    for (int axis = 0; axis < 3; ++axis) {
      // 0.999: the decoded bound is rounded to a float once more.
      EXPECT_LE(held.min[axis], box.min[axis] - 0.999f * grid.w) << "axis " << axis;
      EXPECT_GE(held.max[axis], box.max[axis] + 0.999f * grid.w) << "axis " << axis;
    }
  }
  // The root's box spans the grid but for the steps of margin at each end.
  const Bounds root = compactBounds(compactNode(bvh.nodes[0], grid), grid);
  const Bounds exact = bvhBounds(bvh.nodes[0]);
  const glm::vec3 extent = exact.max - exact.min;
  const float largest = std::max({extent.x, extent.y, extent.z});
  EXPECT_NEAR(largest / grid.w, 65532.0f, 1.0f);
  EXPECT_GE(root.min.x, grid.x);
  EXPECT_LE(root.max.x, grid.x + 65535.0f * grid.w);
}

// The box a compact node holds for a node with the box `box`, in the grid of that box.
Bounds compactedInItsOwnGrid(const Bounds& box) {
  const glm::vec4 grid = nodeGridFor(box);
  return compactBounds(compactNode({glm::vec4(box.min, 0.0f), glm::vec4(box.max, 0.0f)}, grid),
                       grid);
}

// A flat object (a floor: no extent along y) and a point-like one still get a usable grid.
TEST(BvhBuild, CompactNodesOfFlatAndPointObjects) {
  Bounds floor;
  floor.grow(glm::vec3(-5.0f, 0.0f, -5.0f));
  floor.grow(glm::vec3(5.0f, 0.0f, 5.0f));
  const Bounds heldFloor = compactedInItsOwnGrid(floor);
  EXPECT_TRUE(heldFloor.contains(floor));
  EXPECT_LT(heldFloor.max.y - heldFloor.min.y, 4.0f * nodeGridFor(floor).w);

  Bounds point;
  point.grow(glm::vec3(3.0f, 2.0f, 1.0f));
  EXPECT_EQ(nodeGridFor(point).w, 1.0f);
  EXPECT_TRUE(compactedInItsOwnGrid(point).contains(point));
}

TEST(BvhBuild, AnEmptyListGivesOneEmptyLeaf) {
  const TriangleBvh bvh = buildTriangleBvh({}, {});
  ASSERT_EQ(bvh.nodes.size(), 1u);
  EXPECT_EQ(bvhCount(bvh.nodes[0]), 0);
  EXPECT_TRUE(bvhBounds(bvh.nodes[0]).empty());
}

TEST(BvhBuild, TraversalAgreesWithTestingEveryTriangle) {
  const TriangleSoup soup = randomTriangles(2000, 3);
  const TriangleBvh bvh = buildTriangleBvh(soup.positions, soup.triangles);
  std::mt19937 random(4);
  std::uniform_real_distribution<float> around(-0.2f, 1.2f);
  int blocked = 0;
  const int rays = 2000;
  for (int i = 0; i < rays; ++i) {
    const glm::vec3 from(around(random), around(random), around(random));
    const glm::vec3 to(around(random), around(random), around(random));
    const bool expected = bruteForceBlocked(bvh.triangles, from, to - from, 1.0f);
    ASSERT_EQ(bvhBlocked(bvh, from, to - from, 1.0f), expected) << "ray " << i;
    blocked += expected ? 1 : 0;
  }
  // Both outcomes occur, so the agreement says something about each.
  EXPECT_GT(blocked, rays / 10);
  EXPECT_LT(blocked, rays - rays / 10);
}

TEST(BvhBuild, ABoxOverBoxesKeepsTheirOrderInItsPrimitives) {
  std::vector<Bounds> boxes(10);
  for (int i = 0; i < 10; ++i) {
    boxes[static_cast<std::size_t>(i)].grow(glm::vec3(static_cast<float>(i), 0.0f, 0.0f));
    boxes[static_cast<std::size_t>(i)].grow(glm::vec3(static_cast<float>(i) + 0.5f, 1.0f, 1.0f));
  }
  const Bvh bvh = buildBvh(boxes);
  std::vector<std::uint32_t> sorted = bvh.primitives;
  std::sort(sorted.begin(), sorted.end());
  for (std::uint32_t i = 0; i < 10; ++i)
    EXPECT_EQ(sorted[i], i);
  for (const gpu::BvhNode& node : bvh.nodes) {
    if (!bvhIsLeaf(node))
      continue;
    for (int i = bvhFirst(node); i < bvhFirst(node) + bvhCount(node); ++i)
      EXPECT_TRUE(bvhBounds(node).contains(boxes[bvh.primitives[static_cast<std::size_t>(i)]]));
  }
}

TEST(BvhBuild, TransformedBoundsHoldTheMovedCorners) {
  Bounds unit;
  unit.grow(glm::vec3(0.0f));
  unit.grow(glm::vec3(1.0f));
  const glm::mat4 rotated = glm::mat4(glm::vec4(0, 1, 0, 0), glm::vec4(-1, 0, 0, 0),
                                      glm::vec4(0, 0, 2, 0), glm::vec4(5, 0, 0, 1));
  const Bounds moved = transformed(unit, rotated);
  EXPECT_EQ(moved.min, glm::vec3(4.0f, 0.0f, 0.0f));
  EXPECT_EQ(moved.max, glm::vec3(5.0f, 1.0f, 2.0f));
  EXPECT_TRUE(transformed(Bounds{}, rotated).empty());
}

}  // namespace
}  // namespace penumbra
