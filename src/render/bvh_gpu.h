#pragma once
// Exact visibility on the GPU (--visibility bvh, docs/shadows.md): a bottom-level hierarchy per
// object over its triangles in the object's own coordinates (animation is rigid, so it never
// changes), built and uploaded once, plus one in world coordinates for the quad lights; and a
// small top level over the instances, rebuilt and uploaded only when a transform changed.
// shaders/bvh.glsl traverses them.

#include <cstddef>
#include <vector>

#include <glm/glm.hpp>

#include "gl/handles.h"
#include "render/bvh_build.h"
#include "render/scene_gpu.h"
#include "shared.h"

namespace penumbra {

class BvhGpu {
 public:
  // For frame `frame` of sceneGpu's scene (its geometry uploaded for that frame): builds the
  // bottom levels on the first call, and the top level whenever a transform differs from the
  // previous call's.
  void update(const SceneGpu& sceneGpu, int frame);
  // Binds the buffers to the bindings bvh.glsl reads.
  void bind() const;
  // GPU memory of all levels.
  std::size_t bytes() const;
  // How many times the top level was built (a scene that does not move builds it once).
  int topLevelBuilds() const { return topLevelBuilds_; }
  // The instances of the last update, in the top level's order.
  const std::vector<gpu::BvhInstance>& instances() const { return instances_; }

 private:
  struct BottomLevel {
    int object = -1;  // index into Scene::objects; -1: the quad lights, in world coordinates
    int root = 0;     // its root in the bottom-level node buffer
    Bounds bounds;    // in its own coordinates
    glm::vec4 nodeGrid{0.0f};  // its compact nodes' grid (BvhInstance::nodeGrid)
  };
  void buildBottomLevels(const Scene& scene);
  void buildTopLevel(const std::vector<glm::mat4>& worldFromObject);

  bool built_ = false;
  std::vector<BottomLevel> bottomLevels_;
  std::vector<glm::mat4> worldFromObject_;  // per bottom level, of the last top level
  std::vector<gpu::BvhInstance> instances_;
  gpu::BvhHeader header_{};
  int topLevelBuilds_ = 0;
  std::size_t bottomBytes_ = 0;
  std::size_t topBytes_ = 0;
  gl::Buffer headerBuffer_;
  gl::Buffer topNodes_;
  gl::Buffer instanceBuffer_;
  gl::Buffer nodes_;
  gl::Buffer triangles_;
};

}  // namespace penumbra
