#include "render/gather_indirect.h"

#include "gl/uniforms.h"
#include "shared.h"

namespace penumbra {

IndirectGatherPass::IndirectGatherPass()
    : gather_(gl::Program::compute("gather_indirect.comp")),
      combine_(gl::Program::compute("indirect_combine.comp")) {}

void IndirectGatherPass::run(const GBuffer& gbuffer, const Pyramid* pyramid, int level,
                             const VplBuffer& vpls, float planeTolerance,
                             const gl::Texture& radiance, const gl::Texture& indirect) {
  const bool fullResolution = pyramid == nullptr || level == 0;
  const glm::ivec2 size = fullResolution ? gbuffer.size : pyramid->size(level);
  const GLuint positionDepth =
      fullResolution ? gbuffer.positionDepth.id() : pyramid->positionDepth(level);
  const GLuint normal = fullResolution ? gbuffer.normalKind.id() : pyramid->normal(level);
  if (size != irradianceSize_) {
    irradiance_ = gl::Texture(GL_TEXTURE_2D);
    glTextureStorage2D(irradiance_.id(), 1, GL_RGBA32F, size.x, size.y);
    irradianceSize_ = size;
  }
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gpu::kVplBinding, vpls.buffer.id());

  gather_.use();
  gl::setUniform(gather_, "vplCount", vpls.count);
  gl::setUniform(gather_, "fullResolution", fullResolution);
  const GLuint gatherInputs[] = {positionDepth, normal};
  glBindTextures(0, 2, gatherInputs);
  glBindImageTexture(0, irradiance_.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
  glm::uvec3 groups =
      gather_.groupsFor({static_cast<unsigned>(size.x), static_cast<unsigned>(size.y), 1});
  glDispatchCompute(groups.x, groups.y, groups.z);
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);

  combine_.use();
  gl::setUniform(combine_, "scale", fullResolution ? 1 : 1 << level);
  gl::setUniform(combine_, "vplCount", vpls.count);
  gl::setUniform(combine_, "planeTolerance", planeTolerance);
  const GLuint combineInputs[] = {gbuffer.positionDepth.id(),
                                  gbuffer.normalKind.id(),
                                  gbuffer.albedo.id(),
                                  positionDepth,
                                  normal,
                                  irradiance_.id()};
  glBindTextures(0, 6, combineInputs);
  glBindImageTexture(0, radiance.id(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA32F);
  glBindImageTexture(1, indirect.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
  groups = combine_.groupsFor(
      {static_cast<unsigned>(gbuffer.size.x), static_cast<unsigned>(gbuffer.size.y), 1});
  glDispatchCompute(groups.x, groups.y, groups.z);
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT |
                  GL_TEXTURE_UPDATE_BARRIER_BIT);
}

}  // namespace penumbra
