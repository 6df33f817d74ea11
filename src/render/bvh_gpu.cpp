#include "render/bvh_gpu.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <stdexcept>
#include <string>

#include "scene/transform.h"

namespace penumbra {
namespace {

// Shadow rays as the reference casts them (src/reference/reference.cpp): they start this
// fraction of the scene's diagonal off the surface and stop this fraction of the way short of
// the light point, so that the light's own quad does not block them.
constexpr float kSurfaceOffsetOfDiagonal = 1e-4f;
constexpr float kStopShortOfLight = 1e-4f;

template <class T>
std::size_t upload(const gl::Buffer& buffer, const std::vector<T>& data) {
  // Never zero bytes: GL needs a store, even for a scene without triangles.
  const std::size_t bytes = std::max<std::size_t>(data.size() * sizeof(T), 16);
  glNamedBufferData(buffer.id(), static_cast<GLsizeiptr>(bytes),
                    data.empty() ? nullptr : data.data(), GL_STATIC_DRAW);
  return bytes;
}

// Appends a bottom level to the concatenated buffers, its indices made absolute and its nodes
// compacted in the grid of its root's box; returns its root's index.
int append(const TriangleBvh& level, glm::vec4 grid, std::vector<gpu::BvhCompactNode>& nodes,
           std::vector<gpu::BvhTriangle>& triangles) {
  const auto nodeBase = static_cast<int>(nodes.size());
  const auto triangleBase = static_cast<int>(triangles.size());
  // A compact node's `first` has the bits of its word that the count leaves.
  constexpr std::size_t kCompactIndices = std::size_t{1} << (32u - gpu::kBvhCompactCountBits);
  if (nodes.size() + level.nodes.size() > kCompactIndices ||
      triangles.size() + level.triangles.size() > kCompactIndices)
    throw std::length_error("the scene's hierarchies hold more than " +
                            std::to_string(kCompactIndices) + " nodes or triangles");
  for (gpu::BvhNode node : level.nodes) {
    const int base = bvhIsLeaf(node) ? triangleBase : nodeBase;
    node.boundsMin.w = std::bit_cast<float>(bvhFirst(node) + base);
    nodes.push_back(compactNode(node, grid));
  }
  triangles.insert(triangles.end(), level.triangles.begin(), level.triangles.end());
  return nodeBase;
}

}  // namespace

void BvhGpu::buildBottomLevels(const Scene& scene) {
  std::vector<gpu::BvhCompactNode> nodes;
  std::vector<gpu::BvhTriangle> triangles;
  const auto add = [&](int object, const std::vector<glm::vec3>& positions,
                       const std::vector<glm::uvec3>& indices) {
    if (indices.empty())
      return;
    const TriangleBvh level = buildTriangleBvh(positions, indices);
    const Bounds bounds = bvhBounds(level.nodes[0]);
    const glm::vec4 grid = nodeGridFor(bounds);
    bottomLevels_.push_back({object, append(level, grid, nodes, triangles), bounds, grid});
  };
  for (std::size_t object = 0; object < scene.objects.size(); ++object) {
    std::vector<glm::vec3> positions;
    std::vector<glm::uvec3> indices;
    for (const Mesh& mesh : scene.objects[object].model.meshes) {
      const auto first = static_cast<unsigned>(positions.size());
      positions.insert(positions.end(), mesh.positions.begin(), mesh.positions.end());
      for (const glm::uvec3& triangle : mesh.triangles)
        indices.push_back(triangle + first);
    }
    add(static_cast<int>(object), positions, indices);
  }
  // The reference's quad lights block rays too (from behind, or a second light's).
  std::vector<glm::vec3> corners;
  std::vector<glm::uvec3> quads;
  for (const Light& light : scene.lights) {
    if (light.isMesh())
      continue;  // its triangles are its object's
    const auto first = static_cast<unsigned>(corners.size());
    corners.insert(corners.end(), light.quad.corners.begin(), light.quad.corners.end());
    quads.emplace_back(first, first + 1, first + 2);
    quads.emplace_back(first, first + 2, first + 3);
  }
  add(-1, corners, quads);
  bottomBytes_ = upload(nodes_, nodes) + upload(triangles_, triangles);
}

void BvhGpu::buildTopLevel(const std::vector<glm::mat4>& worldFromObject) {
  std::vector<Bounds> boxes;
  std::vector<gpu::BvhInstance> placed;
  for (std::size_t i = 0; i < bottomLevels_.size(); ++i) {
    // A transform that flattens an object to nothing has no inverse; its triangles have no area
    // to block a ray with.
    if (!(std::abs(glm::determinant(worldFromObject[i])) > 0.0f))
      continue;
    const glm::mat4 objectFromWorld = glm::transpose(glm::inverse(worldFromObject[i]));
    placed.push_back({{objectFromWorld[0], objectFromWorld[1], objectFromWorld[2]},
                      glm::ivec4(bottomLevels_[i].root, 0, 0, 0),
                      bottomLevels_[i].nodeGrid});
    boxes.push_back(transformed(bottomLevels_[i].bounds, worldFromObject[i]));
  }
  const Bvh top = buildBvh(boxes);
  instances_.clear();
  for (const std::uint32_t index : top.primitives)
    instances_.push_back(placed[index]);
  header_.counts = glm::ivec4(static_cast<int>(instances_.size()),
                              instances_.empty() ? 0 : static_cast<int>(top.nodes.size()), 0, 0);
  topBytes_ = upload(topNodes_, top.nodes) + upload(instanceBuffer_, instances_);
  worldFromObject_ = worldFromObject;
  ++topLevelBuilds_;
}

void BvhGpu::update(const SceneGpu& sceneGpu, int frame) {
  const Scene& scene = sceneGpu.scene();
  if (!built_) {
    buildBottomLevels(scene);
    built_ = true;
  }
  std::vector<glm::mat4> worldFromObject;
  worldFromObject.reserve(bottomLevels_.size());
  for (const BottomLevel& level : bottomLevels_) {
    worldFromObject.push_back(
        level.object < 0 ? glm::mat4(1.0f)
                         : penumbra::worldFromObject(
                               scene.objects[static_cast<std::size_t>(level.object)].desc, frame));
  }
  if (topLevelBuilds_ == 0 || worldFromObject != worldFromObject_)
    buildTopLevel(worldFromObject);
  const FrameGeometry& geometry = sceneGpu.geometry();
  const float diagonal = glm::length(geometry.boundsMax - geometry.boundsMin);
  header_.rayOffsets =
      glm::vec4(kSurfaceOffsetOfDiagonal * diagonal, kStopShortOfLight, 0.0f, 0.0f);
  glNamedBufferData(headerBuffer_.id(), sizeof(header_), &header_, GL_DYNAMIC_DRAW);
}

void BvhGpu::bind() const {
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gpu::kBvhHeaderBinding, headerBuffer_.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gpu::kBvhTopNodeBinding, topNodes_.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gpu::kBvhInstanceBinding, instanceBuffer_.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gpu::kBvhNodeBinding, nodes_.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gpu::kBvhTriangleBinding, triangles_.id());
}

std::size_t BvhGpu::bytes() const {
  return sizeof(header_) + topBytes_ + bottomBytes_;
}

}  // namespace penumbra
