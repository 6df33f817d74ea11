// The BVH builder of exact visibility (src/render/bvh_build.h): the tree's structure, and a CPU
// walk of its GPU layout (as bvh.glsl does it) against testing every triangle.

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
