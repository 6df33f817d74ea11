#include "render/bvh_build.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cassert>
#include <cmath>
#include <stdexcept>
#include <string>

namespace penumbra {
namespace {

constexpr int kBins = 16;

// A compact node's bounds take 16 bits: the grid's steps run from 0 to 65535, the root box from
// step 1 to step 1 + kGridStepsOverRoot, and each box grows by a step on each side.
constexpr double kGridStepsOverRoot = 65532.0;

gpu::BvhNode makeNode(const Bounds& bounds, int first, int count) {
  return {glm::vec4(bounds.min, std::bit_cast<float>(first)),
          glm::vec4(bounds.max, std::bit_cast<float>(count))};
}

struct Split {
  int axis = -1;
  int bin = 0;  // primitives in bins [0, bin) go left
  float cost = std::numeric_limits<float>::infinity();
};

class Builder {
 public:
  explicit Builder(const std::vector<Bounds>& boxes) : boxes_(boxes) {
    bvh_.primitives.resize(boxes.size());
    for (std::size_t i = 0; i < boxes.size(); ++i)
      bvh_.primitives[i] = static_cast<std::uint32_t>(i);
  }

  Bvh build() {
    bvh_.nodes.emplace_back();
    const int count = static_cast<int>(boxes_.size());
    if (count == 0) {
      bvh_.nodes[0] = makeNode(Bounds{}, 0, 0);
      return std::move(bvh_);
    }
    subdivide(0, 0, count, 0);
    return std::move(bvh_);
  }

 private:
  Bounds boundsOf(int first, int count, bool centres) const {
    Bounds bounds;
    for (int i = first; i < first + count; ++i) {
      const Bounds& box = boxes_[bvh_.primitives[static_cast<std::size_t>(i)]];
      if (centres)
        bounds.grow(box.centre());
      else
        bounds.grow(box);
    }
    return bounds;
  }

  int binOf(const Bounds& box, int axis, const Bounds& centres) const {
    const float extent = centres.max[axis] - centres.min[axis];
    const int bin = static_cast<int>(static_cast<float>(kBins) *
                                     (box.centre()[axis] - centres.min[axis]) / extent);
    return std::clamp(bin, 0, kBins - 1);
  }

  Split bestSplit(int first, int count, const Bounds& centres) const {
    Split best;
    for (int axis = 0; axis < 3; ++axis) {
      if (!(centres.max[axis] > centres.min[axis]))
        continue;
      std::array<Bounds, kBins> binBounds;
      std::array<int, kBins> binCounts{};
      for (int i = first; i < first + count; ++i) {
        const Bounds& box = boxes_[bvh_.primitives[static_cast<std::size_t>(i)]];
        const auto bin = static_cast<std::size_t>(binOf(box, axis, centres));
        binBounds[bin].grow(box);
        ++binCounts[bin];
      }
      // Sweep from the right, then from the left: the cost of every split between bins.
      std::array<float, kBins> rightCost{};
      Bounds right;
      int rightCount = 0;
      for (int bin = kBins - 1; bin > 0; --bin) {
        right.grow(binBounds[static_cast<std::size_t>(bin)]);
        rightCount += binCounts[static_cast<std::size_t>(bin)];
        rightCost[static_cast<std::size_t>(bin)] =
            right.halfArea() * static_cast<float>(rightCount);
      }
      Bounds left;
      int leftCount = 0;
      for (int bin = 1; bin < kBins; ++bin) {
        left.grow(binBounds[static_cast<std::size_t>(bin - 1)]);
        leftCount += binCounts[static_cast<std::size_t>(bin - 1)];
        if (leftCount == 0 || leftCount == count)
          continue;
        const float cost = left.halfArea() * static_cast<float>(leftCount) +
                           rightCost[static_cast<std::size_t>(bin)];
        if (cost < best.cost)
          best = {axis, bin, cost};
      }
    }
    return best;
  }

  // Moves the primitives going left to the front; returns how many there are.
  int partition(int first, int count, const Split& split, const Bounds& centres) {
    const auto begin = bvh_.primitives.begin() + first;
    const auto middle = std::partition(begin, begin + count, [&](std::uint32_t primitive) {
      return binOf(boxes_[primitive], split.axis, centres) < split.bin;
    });
    return static_cast<int>(middle - begin);
  }

  // Halves the list at the median of the centres along their longest axis.
  int medianSplit(int first, int count, const Bounds& centres) {
    const glm::vec3 extent = centres.max - centres.min;
    const int axis = extent.x >= std::max(extent.y, extent.z) ? 0 : (extent.y >= extent.z ? 1 : 2);
    const auto begin = bvh_.primitives.begin() + first;
    std::nth_element(begin, begin + count / 2, begin + count,
                     [&](std::uint32_t a, std::uint32_t b) {
                       return boxes_[a].centre()[axis] < boxes_[b].centre()[axis];
                     });
    return count / 2;
  }

  void subdivide(std::size_t node, int first, int count, int depth) {
    assert(depth < gpu::kBvhStackSize && "the traversal keeps at most one node per level");
    const Bounds bounds = boundsOf(first, count, false);
    if (count <= kBvhLeafSize) {
      bvh_.nodes[node] = makeNode(bounds, first, count);
      return;
    }
    const Bounds centres = boundsOf(first, count, true);
    int leftCount = 0;
    if (depth >= kBvhMedianSplitDepth) {
      leftCount = medianSplit(first, count, centres);
    } else {
      const Split split = bestSplit(first, count, centres);
      // Every centre in one point: no plane separates them, so halve the list as it is.
      leftCount = split.axis >= 0 ? partition(first, count, split, centres) : count / 2;
    }
    const auto children = static_cast<int>(bvh_.nodes.size());
    bvh_.nodes[node] = makeNode(bounds, children, 0);
    bvh_.nodes.emplace_back();
    bvh_.nodes.emplace_back();
    subdivide(static_cast<std::size_t>(children), first, leftCount, depth + 1);
    subdivide(static_cast<std::size_t>(children) + 1, first + leftCount, count - leftCount,
              depth + 1);
  }

  const std::vector<Bounds>& boxes_;
  Bvh bvh_;
};

}  // namespace

void Bounds::grow(glm::vec3 point) {
  min = glm::min(min, point);
  max = glm::max(max, point);
}

void Bounds::grow(const Bounds& other) {
  min = glm::min(min, other.min);
  max = glm::max(max, other.max);
}

float Bounds::halfArea() const {
  if (empty())
    return 0.0f;
  const glm::vec3 extent = max - min;
  return extent.x * extent.y + extent.y * extent.z + extent.z * extent.x;
}

bool Bounds::contains(const Bounds& other) const {
  return other.empty() || (glm::all(glm::lessThanEqual(min, other.min)) &&
                           glm::all(glm::greaterThanEqual(max, other.max)));
}

Bounds transformed(const Bounds& bounds, const glm::mat4& transform) {
  Bounds result;
  if (bounds.empty())
    return result;
  for (int corner = 0; corner < 8; ++corner) {
    const glm::vec3 point((corner & 1) != 0 ? bounds.max.x : bounds.min.x,
                          (corner & 2) != 0 ? bounds.max.y : bounds.min.y,
                          (corner & 4) != 0 ? bounds.max.z : bounds.min.z);
    result.grow(glm::vec3(transform * glm::vec4(point, 1.0f)));
  }
  return result;
}

int bvhFirst(const gpu::BvhNode& node) {
  return std::bit_cast<int>(node.boundsMin.w);
}

int bvhCount(const gpu::BvhNode& node) {
  return std::bit_cast<int>(node.boundsMax.w);
}

Bounds bvhBounds(const gpu::BvhNode& node) {
  return {glm::vec3(node.boundsMin), glm::vec3(node.boundsMax)};
}

Bvh buildBvh(const std::vector<Bounds>& boxes) {
  if (boxes.size() > static_cast<std::size_t>(kBvhMaxPrimitives))
    throw std::length_error("a hierarchy over " + std::to_string(boxes.size()) +
                            " boxes or triangles: at most " + std::to_string(kBvhMaxPrimitives) +
                            " fit one object's");
  return Builder(boxes).build();
}

glm::vec4 nodeGridFor(const Bounds& root) {
  const glm::vec3 extent = root.max - root.min;
  const float largest = std::max({extent.x, extent.y, extent.z});
  const float step =
      largest > 0.0f ? static_cast<float>(static_cast<double>(largest) / kGridStepsOverRoot) : 1.0f;
  return {root.min - step, step};
}

gpu::BvhCompactNode compactNode(const gpu::BvhNode& node, glm::vec4 grid) {
  const auto steps = [&](glm::vec3 point, int axis, bool high) {
    const double at = (static_cast<double>(point[axis]) - static_cast<double>(grid[axis])) /
                      static_cast<double>(grid.w);
    const double rounded = high ? std::ceil(at) + 1.0 : std::floor(at) - 1.0;
    return static_cast<std::uint32_t>(std::clamp(rounded, 0.0, 65535.0));
  };
  const Bounds box = bvhBounds(node);
  const auto first = static_cast<std::uint32_t>(bvhFirst(node));
  const auto count = static_cast<std::uint32_t>(bvhCount(node));
  assert(first < (1u << (32u - gpu::kBvhCompactCountBits)) &&
         count < (1u << gpu::kBvhCompactCountBits) && "first or count beyond their bits");
  return {glm::uvec4(steps(box.min, 0, false) | steps(box.min, 1, false) << 16,
                     steps(box.min, 2, false) | steps(box.max, 0, true) << 16,
                     steps(box.max, 1, true) | steps(box.max, 2, true) << 16,
                     first << gpu::kBvhCompactCountBits | count)};
}

int compactFirst(const gpu::BvhCompactNode& node) {
  return static_cast<int>(node.words.w >> gpu::kBvhCompactCountBits);
}

int compactCount(const gpu::BvhCompactNode& node) {
  return static_cast<int>(node.words.w & ((1u << gpu::kBvhCompactCountBits) - 1u));
}

Bounds compactBounds(const gpu::BvhCompactNode& node, glm::vec4 grid) {
  const glm::uvec4 words = node.words;
  const glm::vec3 low(words.x & 0xffffu, words.x >> 16, words.y & 0xffffu);
  const glm::vec3 high(words.y >> 16, words.z & 0xffffu, words.z >> 16);
  const glm::vec3 origin(grid);
  return {origin + low * grid.w, origin + high * grid.w};
}

TriangleBvh buildTriangleBvh(const std::vector<glm::vec3>& positions,
                             const std::vector<glm::uvec3>& triangles) {
  std::vector<gpu::BvhTriangle> stored(triangles.size());
  std::vector<Bounds> boxes(triangles.size());
  for (std::size_t i = 0; i < triangles.size(); ++i) {
    const glm::vec3 corner = positions[triangles[i].x];
    stored[i] = {glm::vec4(corner, 0.0f), glm::vec4(positions[triangles[i].y] - corner, 0.0f),
                 glm::vec4(positions[triangles[i].z] - corner, 0.0f)};
    // The corners as the traversal sees them (corner + edge, rounded), so that the boxes hold
    // every point it can hit.
    boxes[i].grow(corner);
    boxes[i].grow(corner + glm::vec3(stored[i].edge1));
    boxes[i].grow(corner + glm::vec3(stored[i].edge2));
  }
  Bvh bvh = buildBvh(boxes);
  TriangleBvh result{std::move(bvh.nodes), {}};
  result.triangles.reserve(triangles.size());
  for (const std::uint32_t index : bvh.primitives)
    result.triangles.push_back(stored[index]);
  return result;
}

}  // namespace penumbra
