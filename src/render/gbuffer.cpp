#include "render/gbuffer.h"

#include <stdexcept>
#include <string>
#include <vector>

#include "gl/uniforms.h"
#include "shared.h"

namespace penumbra {

GBuffer::GBuffer(glm::ivec2 size_) : size(size_) {
  const gl::Texture* colourTargets[] = {&positionDepth, &normalKind, &albedo,    &specular,
                                        &emission,      &shadowLift, &faceNormal};
  GLenum drawBuffers[kColourTargets];
  for (int i = 0; i < kColourTargets; ++i) {
    glTextureStorage2D(colourTargets[i]->id(), 1, GL_RGBA32F, size.x, size.y);
    glNamedFramebufferTexture(framebuffer.id(), GL_COLOR_ATTACHMENT0 + static_cast<GLenum>(i),
                              colourTargets[i]->id(), 0);
    drawBuffers[i] = GL_COLOR_ATTACHMENT0 + static_cast<GLenum>(i);
  }
  glTextureStorage2D(depth.id(), 1, GL_DEPTH_COMPONENT32F, size.x, size.y);
  glNamedFramebufferTexture(framebuffer.id(), GL_DEPTH_ATTACHMENT, depth.id(), 0);
  glNamedFramebufferDrawBuffers(framebuffer.id(), kColourTargets, drawBuffers);
}

GBufferPass::GBufferPass(ShadowRayStarts starts, Triangles triangles)
    : starts_(starts),
      triangles_(triangles),
      surfaces_(
          gl::Program::graphics("gbuffer.vert", "gbuffer_surface.frag",
                                starts == ShadowRayStarts::skipped
                                    ? std::vector<std::string>{"PENUMBRA_WITHOUT_SHADOW_RAY_STARTS"}
                                    : std::vector<std::string>{})),
      lights_(gl::Program::graphics("gbuffer.vert", "gbuffer_light.frag")) {
  if (triangles == Triangles::simplifiedForMaps && starts == ShadowRayStarts::written)
    throw std::invalid_argument("the shadow rays' starts need the full triangles");
}

void GBufferPass::run(const Inputs& in, const Outputs& out) const {
  const SceneGpu& scene = in.scene;
  const Camera& camera = in.camera;
  GBuffer& target = out.gbuffer;
  const glm::vec4 zero(0.0f);
  for (GLint i = 0; i < GBuffer::kColourTargets; ++i)
    glClearNamedFramebufferfv(target.framebuffer.id(), GL_COLOR, i, &zero[0]);
  const float farthest = 1.0f;
  glClearNamedFramebufferfv(target.framebuffer.id(), GL_DEPTH, 0, &farthest);

  glBindFramebuffer(GL_FRAMEBUFFER, target.framebuffer.id());
  glViewport(0, 0, target.size.x, target.size.y);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  // Surfaces are two-sided and light quads are seen from both sides: nothing is culled.
  glDisable(GL_CULL_FACE);

  const glm::mat4 clipFromWorld = camera.clipFromView() * camera.viewFromWorld();
  for (const gl::Program* program : {&surfaces_, &lights_}) {
    gl::setUniform(*program, "clipFromWorld", clipFromWorld);
    gl::setUniform(*program, "eyePosition", camera.position);
  }

  surfaces_.use();
  const bool simplified = triangles_ == Triangles::simplifiedForMaps;
  glBindVertexArray(simplified ? scene.mapVertexArray() : scene.surfaceVertexArray());
  const bool startsWritten = starts_ == ShadowRayStarts::written;
  if (startsWritten) {
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gpu::kGeometryVertexBinding,
                     scene.surfaceVertexBuffer());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gpu::kGeometryIndexBinding,
                     scene.surfaceIndexBuffer());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gpu::kGeometryMeshBinding,
                     scene.surfaceMeshBuffer());
    gl::setUniform(surfaces_, "meshCount",
                   static_cast<int>(scene.geometry().meshFirstVertices.size()));
  }
  glBindSampler(0, scene.surfaceSampler());
  glBindSampler(1, scene.emissionSampler());
  for (const FrameGeometry::Batch& batch : scene.batches()) {
    // Most of a light's reflective shadow map's faces see little of the scene: on the dragon's
    // Cornell box only the face along the light's normal sees the dragon, and drawing it in the
    // four others took most of `bounce rsm` (docs/indirect.md).
    if (!camera.maySeeBox(batch.boundsMin, batch.boundsMax))
      continue;
    const SurfaceMaterial& material =
        scene.scene().materials[static_cast<std::size_t>(batch.material)];
    gl::setUniform(surfaces_, "materialAmbient", material.ambient);
    gl::setUniform(surfaces_, "materialDiffuse", material.diffuse);
    gl::setUniform(surfaces_, "materialSpecular", material.specular);
    gl::setUniform(surfaces_, "materialShininess", material.shininess);
    gl::setUniform(surfaces_, "materialTextured", material.texture >= 0);
    gl::setUniform(surfaces_, "materialEmits", material.emits);
    gl::setUniform(surfaces_, "materialEmission", material.emission);
    gl::setUniform(surfaces_, "materialTwoSided", material.twoSided);
    if (startsWritten)
      gl::setUniform(surfaces_, "firstTriangle", batch.firstTriangle);
    glBindTextureUnit(0, scene.texture(material.texture));
    glBindTextureUnit(1, scene.texture(material.emissionTexture));
    const std::uint32_t firstTriangle = simplified ? batch.firstMapTriangle : batch.firstTriangle;
    const std::uint32_t triangleCount = simplified ? batch.mapTriangleCount : batch.triangleCount;
    const auto firstIndexByte =
        static_cast<std::uintptr_t>(firstTriangle) * 3 * sizeof(std::uint32_t);
    glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(triangleCount * 3), GL_UNSIGNED_INT,
                   reinterpret_cast<const void*>(firstIndexByte));
  }

  lights_.use();
  glBindVertexArray(scene.lightVertexArray());
  glBindSampler(0, scene.emissionSampler());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gpu::kLightBinding, scene.lightBuffer());
  std::uintptr_t quad = 0;  // mesh lights are drawn with the surfaces, quads here
  for (int i = 0; i < scene.lightCount(); ++i) {
    const Light& light = scene.scene().lights[static_cast<std::size_t>(i)];
    if (light.isMesh())
      continue;
    gl::setUniform(lights_, "lightIndex", i);
    glBindTextureUnit(0, scene.texture(light.texture));
    const std::uintptr_t firstIndexByte = quad++ * 6 * sizeof(std::uint32_t);
    glDrawElements(GL_TRIANGLES, 6, GL_UNSIGNED_INT, reinterpret_cast<const void*>(firstIndexByte));
  }

  glBindSampler(0, 0);
  glBindSampler(1, 0);
  glBindVertexArray(0);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

}  // namespace penumbra
