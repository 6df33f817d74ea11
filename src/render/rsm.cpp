#include "render/rsm.h"

#include <algorithm>
#include <array>

#include "gl/uniforms.h"
#include "render/readback.h"
#include "shared.h"

namespace penumbra {
namespace {

// A unit vector perpendicular to `normal`.
glm::vec3 perpendicular(glm::vec3 normal) {
  const glm::vec3 other =
      std::abs(normal.x) < 0.9f ? glm::vec3(1.0f, 0.0f, 0.0f) : glm::vec3(0.0f, 1.0f, 0.0f);
  return glm::normalize(glm::cross(normal, other));
}

}  // namespace

ReflectiveShadowMap::ReflectiveShadowMap(int faceSize, int lightCount)
    : faceSize_(faceSize), lightCount_(lightCount) {
  for (int i = 0; i < std::max(lightCount, 1) * gpu::kRsmFaces; ++i)
    faces_.push_back(std::make_unique<GBuffer>(glm::ivec2(faceSize)));
  const glm::ivec2 size = atlasSize();
  for (const gl::Texture* texture : {&positionArea, &normal, &radiance})
    glTextureStorage2D(texture->id(), 1, GL_RGBA32F, size.x, size.y);
}

glm::ivec2 ReflectiveShadowMap::atlasSize() const {
  return {gpu::kRsmFaces * faceSize_, std::max(lightCount_, 1) * faceSize_};
}

ReflectiveShadowMap::Texels ReflectiveShadowMap::read() const {
  const glm::ivec2 size = atlasSize();
  return {readTexture(positionArea.id(), size, RowOrder::BottomFirst),
          readTexture(normal.id(), size, RowOrder::BottomFirst),
          readTexture(radiance.id(), size, RowOrder::BottomFirst)};
}

RsmPass::RsmPass()
    : gbufferPass_(GBufferPass::ShadowRayStarts::skipped,
                   GBufferPass::Triangles::simplifiedForMaps),
      flux_(gl::Program::compute("rsm_flux.comp")) {}

void RsmPass::run(const Inputs& in, const Outputs& out) const {
  const SceneGpu& scene = in.scene;
  const VplBuffer& vpls = in.vpls;
  ReflectiveShadowMap& target = out.maps;
  const FrameGeometry& geometry = scene.geometry();
  const float diagonal = std::max(glm::length(geometry.boundsMax - geometry.boundsMin), 1e-6f);
  const int vplsPerLight = scene.cellsPerSide() * scene.cellsPerSide();
  const int faceSize = target.faceSize();
  for (int light = 0; light < scene.lightCount(); ++light) {
    const Light& sceneLight = scene.scene().lights[static_cast<std::size_t>(light)];
    glm::vec3 normal = sceneLight.quad.normal;
    glm::vec3 centre = 0.25f * (sceneLight.quad.corners[0] + sceneLight.quad.corners[1] +
                                sceneLight.quad.corners[2] + sceneLight.quad.corners[3]);
    // Off the light's own plane by a hair, so that its quad is not drawn into its own map.
    float lift = 1e-4f * diagonal;
    if (sceneLight.isMesh()) {
      // A mesh light's map looks along its mean normal (+y for a closed mesh) from just outside
      // its bounds: an approximation, the map of a curved light is not its own view
      // (docs/mesh-lights.md).
      const MeshLightGeometry& mesh = scene.meshLight(light);
      normal = mesh.meanNormal != glm::vec3(0.0f) ? mesh.meanNormal : glm::vec3(0.0f, 1.0f, 0.0f);
      centre = 0.5f * (mesh.boundsMin + mesh.boundsMax);
      lift += 0.5f * glm::dot(glm::abs(normal), mesh.boundsMax - mesh.boundsMin);
    }
    const glm::vec3 tangent = perpendicular(normal);
    const glm::vec3 bitangent = glm::cross(normal, tangent);
    const glm::vec3 eye = centre + lift * normal;
    const std::array<glm::vec3, gpu::kRsmFaces> axes = {normal, tangent, -tangent, bitangent,
                                                        -bitangent};
    for (int face = 0; face < gpu::kRsmFaces; ++face) {
      const glm::vec3 axis = axes[static_cast<std::size_t>(face)];
      Camera camera;
      camera.position = eye;
      camera.target = eye + axis;
      camera.up = face == 0 ? tangent : normal;
      camera.fovyDegrees = 90.0f;
      // Surfaces nearer than this to the light's centre are left out of its map.
      camera.nearPlane = 1e-3f * diagonal;
      camera.farPlane = 4.0f * diagonal;
      camera.size = glm::ivec2(faceSize);
      GBuffer& gbuffer = target.face(light, face);
      gbufferPass_.run({scene, camera}, {gbuffer});
      glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);

      flux_.use();
      glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gpu::kVplBinding, vpls.buffer.id());
      const GLuint inputs[] = {gbuffer.positionDepth.id(), gbuffer.normalKind.id(),
                               gbuffer.albedo.id()};
      glBindTextures(0, 3, inputs);
      glBindImageTexture(0, target.positionArea.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
      glBindImageTexture(1, target.normal.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
      glBindImageTexture(2, target.radiance.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
      gl::setUniform(flux_, "atlasOffset", glm::ivec2(face * faceSize, light * faceSize));
      gl::setUniform(flux_, "eyePosition", eye);
      gl::setUniform(flux_, "faceAxis", axis);
      gl::setUniform(flux_, "firstVpl", light * vplsPerLight);
      gl::setUniform(flux_, "endVpl", (light + 1) * vplsPerLight);
      const glm::uvec3 groups =
          flux_.groupsFor({static_cast<unsigned>(faceSize), static_cast<unsigned>(faceSize), 1});
      glDispatchCompute(groups.x, groups.y, groups.z);
      glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    }
  }
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT);
}

}  // namespace penumbra
