#include "render/gather_naive.h"

#include <algorithm>
#include <cstddef>

#include "gl/uniforms.h"
#include "render/bindings.h"
#include "shared.h"

namespace penumbra {

NaiveGatherPass::NaiveGatherPass(int shadowRaysPerDispatch, GatherVplSource preferred)
    : shadowRaysPerDispatch_(shadowRaysPerDispatch),
      available_(gatherVplSourceOnThisContext(preferred)) {}

void NaiveGatherPass::run(const Inputs& in, const Outputs& out) const {
  const GBuffer& gbuffer = in.gbuffer;
  const VplBuffer& vpls = in.vpls;
  const ShadowRays* rays = in.rays;
  const GatherVplSource source = gatherVplSource(vpls.count, available_);
  std::optional<ShadowRayProgram>& programs = programs_[static_cast<std::size_t>(source)];
  if (!programs)
    programs.emplace("gather_naive.comp", gatherVplDefines(source));
  const gl::Program& program = programs->forRays(rays);
  program.use();
  gl::setUniform(program, "eyePosition", in.eyePosition);
  gl::setUniform(program, "vplCount", vpls.count);
  gl::setUniform(program, "shadows", rays != nullptr);
  gl::setUniform(program, "visibleFraction", in.visibleFraction);
  if (rays != nullptr)
    rays->bind();
  bindGatherVpls(vpls, source);
  bindSampledTextures({gbuffer.positionDepth, gbuffer.normalKind, gbuffer.albedo, gbuffer.specular,
                       gbuffer.emission, gbuffer.shadowLift, gbuffer.faceNormal});
  bindImageForUpdating(0, out.radiance, GL_RGBA32F);
  // Without shadow rays one dispatch gathers every VPL; with them, batches (gather_naive.comp).
  const int batch = rays != nullptr ? shadowRaysPerDispatch_ : std::max(vpls.count, 1);
  dispatchInVplBatches(program, gbuffer.size, vpls.count, batch);
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT);
}

}  // namespace penumbra
