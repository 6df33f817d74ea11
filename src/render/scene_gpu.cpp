#include "render/scene_gpu.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "gl/dispatch.h"
#include "gl/uniforms.h"
#include "scene/model.h"
#include "scene/transform.h"

namespace penumbra {
namespace {

// Interleaved vertex of both the surface and the light-quad vertex arrays.
struct Vertex {
  glm::vec3 position;
  glm::vec3 normal;
  glm::vec2 uv;
};

void describeVertexArray(GLuint vertexArray, GLuint vertices, GLuint indices) {
  glVertexArrayVertexBuffer(vertexArray, 0, vertices, 0, sizeof(Vertex));
  glVertexArrayElementBuffer(vertexArray, indices);
  const GLuint offsets[] = {offsetof(Vertex, position), offsetof(Vertex, normal),
                            offsetof(Vertex, uv)};
  const GLint components[] = {3, 3, 2};
  for (GLuint attribute = 0; attribute < 3; ++attribute) {
    glEnableVertexArrayAttrib(vertexArray, attribute);
    glVertexArrayAttribFormat(vertexArray, attribute, components[attribute], GL_FLOAT, GL_FALSE,
                              offsets[attribute]);
    glVertexArrayAttribBinding(vertexArray, attribute, 0);
  }
}

int mipLevels(glm::ivec2 size) {
  return 1 + static_cast<int>(std::floor(std::log2(static_cast<float>(std::max(size.x, size.y)))));
}

}  // namespace

template <class T>
void SceneGpu::uploadWhole(const gl::Buffer& buffer, const std::vector<T>& data) {
  // Never zero bytes: GL needs a store, even for a scene without triangles. The data go in
  // separately, since a store larger than the data must not read past their end.
  const std::size_t dataBytes = data.size() * sizeof(T);
  glNamedBufferData(buffer.id(), static_cast<GLsizeiptr>(std::max<std::size_t>(dataBytes, 16)),
                    nullptr, GL_DYNAMIC_DRAW);
  if (dataBytes > 0)
    glNamedBufferSubData(buffer.id(), 0, static_cast<GLsizeiptr>(dataBytes), data.data());
  uploadedBytes_ += dataBytes;
}

SceneGpu::SceneGpu(Scene& scene) : scene_(scene) {
  std::uint32_t firstVertex = 0;
  std::uint32_t firstObjectVertex = 0;
  for (std::size_t index = 0; index < scene_.objects.size(); ++index) {
    const SceneObject& object = scene_.objects[index];
    std::uint32_t vertexCount = 0;
    for (const Mesh& mesh : object.model.meshes)
      vertexCount += static_cast<std::uint32_t>(mesh.positions.size());
    if (!object.desc.animations.empty()) {
      animatedObjects_.push_back(index);
      animatedVertexRanges_.push_back({glm::ivec4(firstObjectVertex, firstVertex, vertexCount, 0)});
      largestAnimatedVertexCount_ = std::max(largestAnimatedVertexCount_, vertexCount);
      firstObjectVertex += vertexCount;
    }
    firstVertex += vertexCount;
  }
  if (!animatedObjects_.empty())
    animateVertices_.emplace(gl::Program::compute("animate_vertices.comp"));

  describeVertexArray(surfaceVertexArray_.id(), surfaceVertices_.id(), surfaceIndices_.id());
  describeVertexArray(mapVertexArray_.id(), surfaceVertices_.id(), mapIndices_.id());
  describeVertexArray(lightVertexArray_.id(), lightVertices_.id(), lightIndices_.id());

  for (std::size_t i = 0; i < scene_.textures.size(); ++i)
    textures_.emplace_back(GL_TEXTURE_2D);
  textureUploaded_.assign(scene_.textures.size(), false);

  const glm::vec4 white(1.0f);
  glTextureStorage2D(white_.id(), 1, GL_RGBA32F, 1, 1);
  glTextureSubImage2D(white_.id(), 0, 0, 0, 1, 1, GL_RGBA, GL_FLOAT, &white);

  glSamplerParameteri(surfaceSampler_.id(), GL_TEXTURE_WRAP_S, GL_REPEAT);
  glSamplerParameteri(surfaceSampler_.id(), GL_TEXTURE_WRAP_T, GL_REPEAT);
  glSamplerParameteri(surfaceSampler_.id(), GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
  glSamplerParameteri(surfaceSampler_.id(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  // Emission is read at full resolution, bilinearly, as the reference renderer reads it.
  glSamplerParameteri(emissionSampler_.id(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glSamplerParameteri(emissionSampler_.id(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  glSamplerParameteri(emissionSampler_.id(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glSamplerParameteri(emissionSampler_.id(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
}

void SceneGpu::update(int frame, double videoSeconds, int cellsPerSide) {
  uploadedBytes_ = 0;
  if (!geometryUploaded_) {
    geometry_ = buildFrameGeometry(scene_, frame);
    uploadGeometry();
    uploadLightQuads();
    uploadObjectVertices();
    geometryUploaded_ = true;
  } else if (!animatedObjects_.empty()) {
    // The CPU's world-space geometry still serves the bounds (voxel grid, RSM, ray offsets) and
    // the batches' boxes, which the G-buffer's view tests.
    geometry_ = buildFrameGeometry(scene_, frame);
  }
  if (!animatedObjects_.empty())
    animateVertices(frame);
  for (std::size_t i = 0; i < textures_.size(); ++i) {
    if (!textureUploaded_[i] || scene_.textures[i]->animated())
      uploadTexture(static_cast<int>(i), videoSeconds);
  }
  const bool vplCountChanged = cellsPerSide != cellsPerSide_;
  cellsPerSide_ = cellsPerSide;
  // cellsPerSide_ is 0 before the first frame, so the first frame uploads the lights.
  bool lightsChanged = vplCountChanged;
  for (std::size_t i = 0; i < scene_.lights.size(); ++i)
    lightsChanged = lightsChanged || meshLightChanges(i);
  if (lightsChanged) {
    updateMeshLights(frame, videoSeconds);
    uploadLights();
  }
}

bool SceneGpu::meshLightChanges(std::size_t index) const {
  const Light& light = scene_.lights[index];
  if (!light.isMesh())
    return false;
  const bool animatedTexture =
      light.texture >= 0 && scene_.textures[static_cast<std::size_t>(light.texture)]->animated();
  return animatedTexture ||
         !scene_.objects[static_cast<std::size_t>(light.object)].desc.animations.empty();
}

void SceneGpu::updateMeshLights(int frame, double videoSeconds) {
  meshLights_.assign(scene_.lights.size(), {});
  meshLightVpls_.assign(scene_.lights.size(), {});
  for (std::size_t i = 0; i < scene_.lights.size(); ++i) {
    const Light& light = scene_.lights[i];
    if (!light.isMesh())
      continue;
    meshLights_[i] = meshLightGeometry(scene_, light, frame);
    const Image* texture =
        light.texture < 0
            ? nullptr
            : &scene_.textures[static_cast<std::size_t>(light.texture)]->frameAt(videoSeconds);
    meshLightVpls_[i] = makeMeshVpls(meshLights_[i], light.emission, texture, light.twoSided,
                                     cellsPerSide_ * cellsPerSide_);
  }
}

GLuint SceneGpu::texture(int index) const {
  return index < 0 ? white_.id() : textures_[static_cast<std::size_t>(index)].id();
}

void SceneGpu::uploadGeometry() {
  std::vector<Vertex> vertices(geometry_.positions.size());
  for (std::size_t i = 0; i < vertices.size(); ++i)
    vertices[i] = {geometry_.positions[i], geometry_.normals[i], geometry_.uvs[i]};
  uploadWhole(surfaceVertices_, vertices);
  uploadWhole(surfaceIndices_, geometry_.triangles);
  uploadWhole(mapIndices_, geometry_.mapTriangles);
  uploadWhole(surfaceMeshFirstVertices_, geometry_.meshFirstVertices);
}

void SceneGpu::uploadObjectVertices() {
  if (animatedObjects_.empty())
    return;
  std::vector<Vertex> vertices;
  for (const std::size_t object : animatedObjects_) {
    for (const Mesh& mesh : scene_.objects[object].model.meshes) {
      for (std::size_t i = 0; i < mesh.positions.size(); ++i)
        vertices.push_back({mesh.positions[i], mesh.normals[i], mesh.uvs[i]});
    }
  }
  uploadWhole(objectVertices_, vertices);
  uploadWhole(objectVertexRanges_, animatedVertexRanges_);
  // The transforms change every frame but not their number: one store, rewritten per frame.
  glNamedBufferData(
      objectTransforms_.id(),
      static_cast<GLsizeiptr>(animatedObjects_.size() * sizeof(gpu::GpuObjectTransform)), nullptr,
      GL_DYNAMIC_DRAW);
}

// The transforms are the CPU's (buildFrameGeometry's), so the vertices are too, up to rounding.
void SceneGpu::animateVertices(int frame) {
  std::vector<gpu::GpuObjectTransform> transforms;
  for (const std::size_t object : animatedObjects_) {
    const glm::mat4 worldFromModel = worldFromObject(scene_.objects[object].desc, frame);
    const glm::mat3 normalTransform = normalMatrix(worldFromModel);
    gpu::GpuObjectTransform& transform = transforms.emplace_back();
    for (int column = 0; column < 4; ++column)
      transform.worldFromObject[column] = worldFromModel[column];
    for (int column = 0; column < 3; ++column)
      transform.normalTransform[column] = glm::vec4(normalTransform[column], 0.0f);
  }
  const std::size_t transformBytes = transforms.size() * sizeof(gpu::GpuObjectTransform);
  glNamedBufferSubData(objectTransforms_.id(), 0, static_cast<GLsizeiptr>(transformBytes),
                       transforms.data());
  uploadedBytes_ += transformBytes;

  animateVertices_->use();
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gpu::kObjectVertexBinding, objectVertices_.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gpu::kObjectTransformBinding, objectTransforms_.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gpu::kObjectVertexRangeBinding,
                   objectVertexRanges_.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gpu::kGeometryVertexBinding, surfaceVertices_.id());
  // Objects of more vertices than one dispatch's work groups hold take several dispatches.
  const unsigned verticesPerDispatch =
      gl::kMaxWorkGroupsPerDimension * static_cast<unsigned>(gpu::kAnimateGroupSize);
  for (unsigned first = 0; first < largestAnimatedVertexCount_; first += verticesPerDispatch) {
    gl::setUniform(*animateVertices_, "firstVertex", first);
    const unsigned count = std::min(largestAnimatedVertexCount_ - first, verticesPerDispatch);
    const glm::uvec3 groups = animateVertices_->groupsFor({count, 1u, 1u});
    glDispatchCompute(groups.x, static_cast<GLuint>(animatedObjects_.size()), 1);
  }
  // The G-buffer reads the vertices as attributes, voxelization and the RSM as storage.
  glMemoryBarrier(GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
}

// The quads do not move: Light::quad is the scene's, at every frame.
void SceneGpu::uploadLightQuads() {
  std::vector<Vertex> lightVertices;
  std::vector<glm::uvec3> lightTriangles;
  const glm::vec2 cornerUv[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  quadLightCount_ = 0;
  for (const Light& light : scene_.lights) {
    if (light.isMesh())
      continue;
    ++quadLightCount_;
    const auto first = static_cast<std::uint32_t>(lightVertices.size());
    for (int corner = 0; corner < 4; ++corner)
      lightVertices.push_back({light.quad.corners[corner], light.quad.normal, cornerUv[corner]});
    lightTriangles.push_back({first, first + 1, first + 2});
    lightTriangles.push_back({first, first + 2, first + 3});
  }
  uploadWhole(lightVertices_, lightVertices);
  uploadWhole(lightIndices_, lightTriangles);
}

SceneGpu::StagingBuffer::StagingBuffer(std::size_t bytesPerFrame) : slotBytes(bytesPerFrame) {
  constexpr GLbitfield kFlags = GL_MAP_WRITE_BIT | GL_MAP_PERSISTENT_BIT | GL_MAP_COHERENT_BIT;
  const auto totalBytes = static_cast<GLsizeiptr>(slotBytes * kStagingSlots);
  glNamedBufferStorage(buffer.id(), totalBytes, nullptr, kFlags);
  mapped = static_cast<std::byte*>(glMapNamedBufferRange(buffer.id(), 0, totalBytes, kFlags));
}

SceneGpu::StagingBuffer::~StagingBuffer() {
  // Deleting the buffer unmaps it.
  for (GLsync fence : fences) {
    if (fence != nullptr)
      glDeleteSync(fence);
  }
}

void SceneGpu::uploadTexture(int index, double seconds) {
  const auto textureIndex = static_cast<std::size_t>(index);
  TextureSource& source = *scene_.textures[textureIndex];
  const Image& picture = source.frameAt(seconds);
  const gl::Texture& texture = textures_[textureIndex];
  if (!textureUploaded_[textureIndex]) {
    glTextureStorage2D(texture.id(), mipLevels({picture.width, picture.height}), GL_RGBA32F,
                       picture.width, picture.height);
    textureUploaded_[textureIndex] = true;
  }
  const std::size_t rowBytes = static_cast<std::size_t>(picture.width) * sizeof(glm::vec4);
  if (!source.animated()) {
    // GL's first row is v = 0, the bottom of the picture; Image row 0 is its top.
    for (int row = 0; row < picture.height; ++row) {
      glTextureSubImage2D(texture.id(), 0, 0, picture.height - 1 - row, picture.width, 1, GL_RGBA,
                          GL_FLOAT, &picture.at(0, row));
    }
  } else {
    stagingBuffers_.resize(textures_.size());
    if (!stagingBuffers_[textureIndex])
      stagingBuffers_[textureIndex] = std::make_unique<StagingBuffer>(rowBytes * picture.height);
    StagingBuffer& staging = *stagingBuffers_[textureIndex];
    GLsync& fence = staging.fences[static_cast<std::size_t>(staging.nextSlot)];
    if (fence != nullptr) {
      // The slot's last upload was kStagingSlots frames ago; its copy has finished by now unless
      // the GPU runs that far behind.
      while (glClientWaitSync(fence, GL_SYNC_FLUSH_COMMANDS_BIT, 1'000'000'000) ==
             GL_TIMEOUT_EXPIRED) {
      }
      glDeleteSync(fence);
    }
    const std::size_t offset = staging.slotBytes * static_cast<std::size_t>(staging.nextSlot);
    // Flipped as above: the buffer holds GL's bottom row first.
    for (int row = 0; row < picture.height; ++row) {
      std::memcpy(staging.mapped + offset + rowBytes * static_cast<std::size_t>(row),
                  &picture.at(0, picture.height - 1 - row), rowBytes);
    }
    glBindBuffer(GL_PIXEL_UNPACK_BUFFER, staging.buffer.id());
    glTextureSubImage2D(texture.id(), 0, 0, 0, picture.width, picture.height, GL_RGBA, GL_FLOAT,
                        reinterpret_cast<const void*>(offset));
    glBindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
    fence = glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
    staging.nextSlot = (staging.nextSlot + 1) % kStagingSlots;
  }
  uploadedBytes_ += rowBytes * static_cast<std::size_t>(picture.height);
  glGenerateTextureMipmap(texture.id());
}

void SceneGpu::uploadLights() {
  std::vector<gpu::GpuLight> lights;
  const int vplsPerLight = cellsPerSide_ * cellsPerSide_;
  for (std::size_t i = 0; i < scene_.lights.size(); ++i) {
    const Light& light = scene_.lights[i];
    gpu::GpuLight gpuLight{};
    if (light.isMesh()) {
      const MeshLightGeometry& mesh = meshLights_[i];
      gpuLight.corners[0] = glm::vec4(mesh.boundsMin, 1.0f);
      gpuLight.corners[1] = glm::vec4(mesh.boundsMax, 1.0f);
      gpuLight.normalArea = glm::vec4(mesh.meanNormal, static_cast<float>(mesh.area));
    } else {
      for (int corner = 0; corner < 4; ++corner)
        gpuLight.corners[corner] = glm::vec4(light.quad.corners[corner], 1.0f);
      gpuLight.normalArea = glm::vec4(light.quad.normal, light.quad.area);
    }
    gpuLight.emission = glm::vec4(light.emission, 0.0f);
    gpuLight.vplInfo = glm::ivec4(static_cast<int>(i) * vplsPerLight, cellsPerSide_,
                                  light.texture >= 0 ? 1 : 0, light.isMesh() ? 1 : 0);
    lights.push_back(gpuLight);
  }
  uploadWhole(lights_, lights);
}

}  // namespace penumbra
