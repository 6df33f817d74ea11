#include "render/gather_naive.h"

#include <algorithm>

#include "gl/uniforms.h"
#include "render/bindings.h"
#include "shared.h"

namespace penumbra {

NaiveGatherPass::NaiveGatherPass(int shadowRaysPerDispatch)
    : program_("gather_naive.comp"), shadowRaysPerDispatch_(shadowRaysPerDispatch) {}

void NaiveGatherPass::run(const Inputs& in, const Outputs& out) const {
  const GBuffer& gbuffer = in.gbuffer;
  const VplBuffer& vpls = in.vpls;
  const ShadowRays* rays = in.rays;
  const gl::Program& program = program_.forRays(rays);
  program.use();
  gl::setUniform(program, "eyePosition", in.eyePosition);
  gl::setUniform(program, "vplCount", vpls.count);
  gl::setUniform(program, "shadows", rays != nullptr);
  gl::setUniform(program, "visibleFraction", in.visibleFraction);
  if (rays != nullptr)
    rays->bind();
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gpu::kVplBinding, vpls.buffer.id());
  bindSampledTextures({gbuffer.positionDepth, gbuffer.normalKind, gbuffer.albedo, gbuffer.specular,
                       gbuffer.emission, gbuffer.shadowLift, gbuffer.faceNormal});
  bindImageForUpdating(0, out.radiance, GL_RGBA32F);
  // Without shadow rays one dispatch gathers every VPL; with them, batches (gather_naive.comp).
  const int batch = rays != nullptr ? shadowRaysPerDispatch_ : std::max(vpls.count, 1);
  dispatchInVplBatches(program, gbuffer.size, vpls.count, batch);
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT);
}

}  // namespace penumbra
