#include "render/upsample.h"

#include "gl/dispatch.h"
#include "gl/uniforms.h"
#include "render/bindings.h"

namespace penumbra {

UpsamplePass::UpsamplePass()
    : levelProgram_(gl::Program::compute("upsample.comp")),
      radianceProgram_(gl::Program::compute("upsample.comp", {"PENUMBRA_WRITES_RADIANCE"})) {}

void UpsamplePass::run(const Inputs& in, const Outputs& out) const {
  for (int level = in.refinement.layout().coarsest(); level > 0; --level)
    runLevel(levelProgram_, level, in, out.gathered);
  bindImageForWriting(3, out.radiance, GL_RGBA32F);
  runLevel(radianceProgram_, 0, in, out.gathered);
}

void UpsamplePass::completeFullResolution(const Inputs& in, GatheredLevels& gathered) const {
  runLevel(levelProgram_, 0, in, gathered);
}

void UpsamplePass::runLevel(const gl::Program& program, int level, const Inputs& in,
                            GatheredLevels& gathered) const {
  const LevelLayout& layout = in.refinement.layout();
  const bool hasCoarser = level < layout.coarsest();
  // The coarsest level has no coarser one; its own textures stand in, never read.
  const int coarser = hasCoarser ? level + 1 : level;
  bindSampledTextures({in.reduced.positionDepth(level), in.reduced.normal(level),
                       in.reduced.positionDepth(coarser), in.reduced.normal(coarser),
                       gathered.diffuse(coarser), gathered.specular(coarser), in.gbuffer.albedo,
                       in.gbuffer.emission});
  bindImageForReading(0, in.refinement.state(level), GL_R32UI);
  bindImageForUpdating(1, gathered.diffuse(level), GL_RGBA32F);
  bindImageForUpdating(2, gathered.specular(level), GL_RGBA32F);
  gl::setUniform(program, "planeTolerance", in.planeTolerance);
  gl::setUniform(program, "level", level);
  gl::setUniform(program, "hasCoarser", hasCoarser);
  // upsample.comp: an invocation per 4x4 block of texels.
  gl::dispatchThreads(program, (layout.size(level) + 3) / 4);
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
}

}  // namespace penumbra
