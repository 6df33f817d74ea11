#include "render/gather_indirect.h"

#include <algorithm>

#include "gl/uniforms.h"
#include "render/bindings.h"
#include "shared.h"

namespace penumbra {

IndirectGatherPass::IndirectGatherPass(int shadowRaysPerDispatch)
    : gather_("gather_indirect.comp"),
      combine_("indirect_combine.comp"),
      shadowRaysPerDispatch_(shadowRaysPerDispatch) {}

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

  if (in.rays != nullptr)
    in.rays->bind();
  // Without shadow rays one dispatch gathers every VPL; with them, batches (gather_indirect.comp).
  const int allVpls = std::max(vpls.count, 1);
  const int batch = in.rays != nullptr ? shadowRaysPerDispatch_ : allVpls;

  const gl::Program& gather = gather_.forRays(in.rays);
  gather.use();
  gl::setUniform(gather, "fullResolution", fullResolution);
  bindSampledTextures({positionDepth, normal});
  bindImageForUpdating(0, irradiance_, GL_RGBA32F);
  dispatchInVplBatches(gather, size, vpls.count, batch);

  const gl::Program& combine = combine_.forRays(in.rays);
  combine.use();
  gl::setUniform(combine, "scale", fullResolution ? 1 : 1 << level);
  gl::setUniform(combine, "planeTolerance", in.planeTolerance);
  bindSampledTextures({gbuffer.positionDepth, gbuffer.normalKind, gbuffer.albedo, positionDepth,
                       normal, irradiance_});
  bindImageForUpdating(0, out.radiance, GL_RGBA32F);
  bindImageForUpdating(1, out.indirect, GL_RGBA32F);
  // At full resolution no pixel gathers exactly: one dispatch takes the gathered irradiance.
  dispatchInVplBatches(combine, gbuffer.size, vpls.count, fullResolution ? allVpls : batch);
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT);
}

}  // namespace penumbra
