#pragma once
// The scene's data on the GPU for one frame: world-space geometry, the light quads, the light
// list and every texture at the frame's time. update() uploads everything on the first frame,
// and afterwards only what changed: the transforms of animated objects, the frames of video
// textures, and the light list when the VPL count or an animated mesh light changes it. An
// animated object's object-space vertices stay on the GPU, and a compute pass
// (animate_vertices.comp) writes its world-space vertices into the surface vertex buffer at every
// frame, the first included, so that every pass reads one buffer. A static scene uploads nothing
// after its first frame; uploadedBytes() counts each frame's bytes.

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "gl/handles.h"
#include "gl/program.h"
#include "scene/mesh_light.h"
#include "scene/scene.h"
#include "shared.h"

namespace penumbra {

class SceneGpu {
 public:
  explicit SceneGpu(Scene& scene);

  // Uploads frame `frame`: geometry (animation), the animated textures (video) at
  // `videoSeconds`, and the light list with room for cellsPerSide^2 VPLs per light.
  void update(int frame, double videoSeconds, int cellsPerSide);

  const Scene& scene() const { return scene_; }
  // Bytes the last update() sent to the GPU: geometry, textures and the light list.
  std::uint64_t uploadedBytes() const { return uploadedBytes_; }
  GLuint surfaceVertexArray() const { return surfaceVertexArray_.id(); }
  // The same vertices with the reflective shadow maps' triangles (FrameGeometry::mapTriangles).
  GLuint mapVertexArray() const { return mapVertexArray_.id(); }
  GLuint lightVertexArray() const { return lightVertexArray_.id(); }
  // This frame's batches: their triangles are the same at every frame, their boxes follow the
  // animation.
  const std::vector<FrameGeometry::Batch>& batches() const { return geometry_.batches; }
  int lightCount() const { return static_cast<int>(scene_.lights.size()); }
  int cellsPerSide() const { return cellsPerSide_; }
  int vplCount() const { return lightCount() * cellsPerSide_ * cellsPerSide_; }
  GLuint lightBuffer() const { return lights_.id(); }
  // A scene texture, or a white 1x1 texture for -1.
  GLuint texture(int index) const;
  // Repeat and trilinear filtering for surfaces; clamp and bilinear for emission.
  GLuint surfaceSampler() const { return surfaceSampler_.id(); }
  GLuint emissionSampler() const { return emissionSampler_.id(); }
  const FrameGeometry& geometry() const { return geometry_; }
  // The vertex and index buffers (kFloatsPerVertex floats per vertex, three indices per
  // triangle), for passes that read the triangles directly.
  GLuint surfaceVertexBuffer() const { return surfaceVertices_.id(); }
  GLuint surfaceIndexBuffer() const { return surfaceIndices_.id(); }
  // FrameGeometry::meshFirstVertices, for the G-buffer's mesh of each pixel.
  GLuint surfaceMeshBuffer() const { return surfaceMeshFirstVertices_.id(); }
  unsigned surfaceTriangleCount() const {
    return static_cast<unsigned>(geometry_.triangles.size());
  }
  GLuint lightVertexBuffer() const { return lightVertices_.id(); }
  GLuint lightIndexBuffer() const { return lightIndices_.id(); }
  // Two triangles per quad light (mesh lights' triangles are the surfaces').
  unsigned lightTriangleCount() const { return 2u * static_cast<unsigned>(quadLightCount_); }
  // A mesh light's triangles at this frame (light `index` must be a mesh light).
  const MeshLightGeometry& meshLight(int index) const {
    return meshLights_[static_cast<std::size_t>(index)];
  }
  // A mesh light's VPLs at this frame, made on the CPU (makeMeshVpls); empty for a quad light.
  const std::vector<Vpl>& meshLightVpls(int index) const {
    return meshLightVpls_[static_cast<std::size_t>(index)];
  }

 private:
  void uploadGeometry();
  void uploadObjectVertices();
  void animateVertices(int frame);
  void uploadLightQuads();
  void uploadTexture(int index, double seconds);
  void uploadLights();
  void updateMeshLights(int frame, double videoSeconds);
  // Whether light `index`'s mesh light changes from frame to frame (its object is animated or
  // its texture is a video).
  bool meshLightChanges(std::size_t index) const;
  template <class T>
  void uploadWhole(const gl::Buffer& buffer, const std::vector<T>& data);

  Scene& scene_;
  FrameGeometry geometry_;
  gl::Buffer surfaceVertices_;
  gl::Buffer surfaceIndices_;
  gl::Buffer surfaceMeshFirstVertices_;
  gl::VertexArray surfaceVertexArray_;
  gl::Buffer mapIndices_;
  gl::VertexArray mapVertexArray_;
  gl::Buffer lightVertices_;
  gl::Buffer lightIndices_;
  gl::VertexArray lightVertexArray_;
  gl::Buffer lights_;
  std::vector<gl::Texture> textures_;
  std::vector<bool> textureUploaded_;
  // Video frames go through a persistently mapped buffer of kStagingSlots frames, so that
  // writing a frame never waits for the GPU to finish reading an earlier one: each slot is
  // reused only after the fence of its last upload has signalled (normally long before).
  static constexpr int kStagingSlots = 3;
  struct StagingBuffer {
    gl::Buffer buffer;
    std::byte* mapped = nullptr;
    std::size_t slotBytes = 0;
    std::array<GLsync, kStagingSlots> fences{};
    int nextSlot = 0;
    explicit StagingBuffer(std::size_t bytesPerFrame);
    ~StagingBuffer();
    StagingBuffer(const StagingBuffer&) = delete;
    StagingBuffer& operator=(const StagingBuffer&) = delete;
  };
  std::vector<std::unique_ptr<StagingBuffer>> stagingBuffers_;  // per texture; null for stills
  gl::Texture white_{GL_TEXTURE_2D};
  gl::Sampler surfaceSampler_;
  gl::Sampler emissionSampler_;
  int cellsPerSide_ = 0;
  int quadLightCount_ = 0;
  bool geometryUploaded_ = false;
  // The animated objects (indices into scene_.objects), where their vertices lie in the
  // object-space and surface vertex buffers (buildFrameGeometry writes the objects' vertices in
  // order), and the pass that transforms them; no pass for a scene without animation.
  std::vector<std::size_t> animatedObjects_;
  std::vector<gpu::GpuObjectVertexRange> animatedVertexRanges_;
  std::uint32_t largestAnimatedVertexCount_ = 0;
  gl::Buffer objectVertices_;
  gl::Buffer objectVertexRanges_;
  gl::Buffer objectTransforms_;
  std::optional<gl::Program> animateVertices_;
  std::uint64_t uploadedBytes_ = 0;
  std::vector<MeshLightGeometry> meshLights_;  // per light; empty for a quad light
  std::vector<std::vector<Vpl>> meshLightVpls_;
};

}  // namespace penumbra
