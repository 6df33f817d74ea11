#include "render/upsample.h"

#include "gl/dispatch.h"
#include "gl/uniforms.h"
#include "render/bindings.h"

namespace penumbra {

UpsamplePass::UpsamplePass() : program_(gl::Program::compute("upsample.comp")) {}

void UpsamplePass::run(const Inputs& in, const Outputs& out) const {
  const LevelLayout& layout = in.refinement.layout();
  const GatheredLevels& coarserLevels = out.gathered;
  gl::setUniform(program_, "planeTolerance", in.planeTolerance);
  bindImageForWriting(3, out.radiance, GL_RGBA32F);
  for (int level = layout.coarsest(); level >= 0; --level) {
    const bool hasCoarser = level < layout.coarsest();
    // The coarsest level has no coarser one; its own textures stand in, never read.
    const int coarser = hasCoarser ? level + 1 : level;
    bindSampledTextures({in.reduced.positionDepth(level), in.reduced.normal(level),
                         in.reduced.positionDepth(coarser), in.reduced.normal(coarser),
                         coarserLevels.diffuse(coarser), coarserLevels.specular(coarser),
                         in.gbuffer.albedo, in.gbuffer.emission});
    bindImageForReading(0, in.refinement.state(level), GL_R32UI);
    bindImageForUpdating(1, out.gathered.diffuse(level), GL_RGBA32F);
    bindImageForUpdating(2, out.gathered.specular(level), GL_RGBA32F);
    gl::setUniform(program_, "level", level);
    gl::setUniform(program_, "hasCoarser", hasCoarser);
    gl::setUniform(program_, "writeRadiance", level == 0);
    // upsample.comp: an invocation per 2x2 block of texels.
    gl::dispatchThreads(program_, (layout.size(level) + 1) / 2);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
  }
}

}  // namespace penumbra
