#include "render/upsample.h"

#include "gl/dispatch.h"
#include "gl/uniforms.h"

namespace penumbra {

UpsamplePass::UpsamplePass() : program_(gl::Program::compute("upsample.comp")) {}

void UpsamplePass::run(const GBuffer& gbuffer, const Pyramid& pyramid, float planeTolerance,
                       const gl::Texture& radiance) const {
  gl::setUniform(program_, "planeTolerance", planeTolerance);
  glBindImageTexture(3, radiance.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
  for (int level = pyramid.levelCount() - 1; level >= 0; --level) {
    const bool hasCoarser = level + 1 < pyramid.levelCount();
    // The coarsest level has no coarser one; its own textures stand in, never read.
    const int coarser = hasCoarser ? level + 1 : level;
    const GLuint inputs[] = {pyramid.positionDepth(level),
                             pyramid.normal(level),
                             pyramid.positionDepth(coarser),
                             pyramid.normal(coarser),
                             pyramid.diffuseResult(coarser),
                             pyramid.specularResult(coarser),
                             gbuffer.albedo.id(),
                             gbuffer.emission.id()};
    glBindTextures(0, 8, inputs);
    glBindImageTexture(0, pyramid.state(level), 0, GL_FALSE, 0, GL_READ_ONLY, GL_R32UI);
    glBindImageTexture(1, pyramid.diffuseResult(level), 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA32F);
    glBindImageTexture(2, pyramid.specularResult(level), 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA32F);
    gl::setUniform(program_, "level", level);
    gl::setUniform(program_, "hasCoarser", hasCoarser);
    gl::setUniform(program_, "writeRadiance", level == 0);
    gl::dispatchThreads(program_, pyramid.size(level));
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
  }
}

}  // namespace penumbra
