#include "render/gather_indirect.h"

#include "gl/uniforms.h"
#include "render/bindings.h"
#include "shared.h"

namespace penumbra {

IndirectGatherPass::IndirectGatherPass()
    : gather_(gl::Program::compute("gather_indirect.comp")),
      combine_(gl::Program::compute("indirect_combine.comp")) {}

void IndirectGatherPass::run(const Inputs& in, const Outputs& out) {
  const GBuffer& gbuffer = in.gbuffer;
  const VplBuffer& vpls = in.vpls;
  const int level = in.level;
  const bool fullResolution = in.reduced == nullptr || level == 0;
  const glm::ivec2 size = fullResolution ? gbuffer.size : in.reduced->layout().size(level);
  const gl::Texture& positionDepth =
      fullResolution ? gbuffer.positionDepth : in.reduced->positionDepth(level);
  const gl::Texture& normal = fullResolution ? gbuffer.normalKind : in.reduced->normal(level);
  if (size != irradianceSize_) {
    irradiance_ = gl::Texture(GL_TEXTURE_2D);
    glTextureStorage2D(irradiance_.id(), 1, GL_RGBA32F, size.x, size.y);
    irradianceSize_ = size;
  }
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gpu::kVplBinding, vpls.buffer.id());

  gather_.use();
  gl::setUniform(gather_, "vplCount", vpls.count);
  gl::setUniform(gather_, "fullResolution", fullResolution);
  bindSampledTextures({positionDepth, normal});
  bindImageForWriting(0, irradiance_, GL_RGBA32F);
  glm::uvec3 groups =
      gather_.groupsFor({static_cast<unsigned>(size.x), static_cast<unsigned>(size.y), 1});
  glDispatchCompute(groups.x, groups.y, groups.z);
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);

  combine_.use();
  gl::setUniform(combine_, "scale", fullResolution ? 1 : 1 << level);
  gl::setUniform(combine_, "vplCount", vpls.count);
  gl::setUniform(combine_, "planeTolerance", in.planeTolerance);
  bindSampledTextures({gbuffer.positionDepth, gbuffer.normalKind, gbuffer.albedo, positionDepth,
                       normal, irradiance_});
  bindImageForUpdating(0, out.radiance, GL_RGBA32F);
  bindImageForWriting(1, out.indirect, GL_RGBA32F);
  groups = combine_.groupsFor(
      {static_cast<unsigned>(gbuffer.size.x), static_cast<unsigned>(gbuffer.size.y), 1});
  glDispatchCompute(groups.x, groups.y, groups.z);
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT |
                  GL_TEXTURE_UPDATE_BARRIER_BIT);
}

}  // namespace penumbra
