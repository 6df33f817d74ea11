#include "render/discontinuity.h"

#include "gl/dispatch.h"
#include "gl/uniforms.h"

namespace penumbra {

DiscontinuityPass::DiscontinuityPass()
    : detect_(gl::Program::compute("discontinuity.comp")),
      reduce_(gl::Program::compute("pyramid_reduce.comp")) {}

void DiscontinuityPass::run(const GBuffer& gbuffer, const Pyramid& pyramid) const {
  const GLuint gbufferInputs[] = {gbuffer.positionDepth.id(), gbuffer.normalKind.id(),
                                  gbuffer.specular.id()};
  glBindTextures(0, 3, gbufferInputs);
  glBindImageTexture(0, pyramid.discontinuity(0), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
  gl::dispatchThreads(detect_, gbuffer.size);
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);

  for (int level = 1; level < pyramid.levelCount(); ++level) {
    const int finer = level - 1;
    const GLuint inputs[] = {pyramid.positionDepth(finer), pyramid.normal(finer),
                             pyramid.specular(finer), pyramid.discontinuity(finer)};
    glBindTextures(0, 4, inputs);
    const GLuint outputs[] = {pyramid.positionDepth(level), pyramid.normal(level),
                              pyramid.specular(level), pyramid.discontinuity(level)};
    for (GLuint unit = 0; unit < 4; ++unit)
      glBindImageTexture(unit, outputs[unit], 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    gl::setUniform(reduce_, "finerIsGBuffer", finer == 0);
    gl::dispatchThreads(reduce_, pyramid.size(level));
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
  }
}

}  // namespace penumbra
