#include "render/gather_hierarchical.h"

#include "gl/uniforms.h"
#include "shared.h"

namespace penumbra {

HierarchicalGatherPass::HierarchicalGatherPass()
    : program_(gl::Program::compute("gather_hierarchical.comp")) {}

void HierarchicalGatherPass::begin(const Pyramid& pyramid, const VplBuffer& vpls,
                                   glm::vec3 eyePosition, const VisibilityMasks* masks,
                                   bool visibleFraction) const {
  program_.use();
  gl::setUniform(program_, "eyePosition", eyePosition);
  gl::setUniform(program_, "vplCount", vpls.count);
  gl::setUniform(program_, "shadows", masks != nullptr);
  gl::setUniform(program_, "visibleFraction", visibleFraction);
  gl::setUniform(program_, "wordsPerMask", masks != nullptr ? masks->wordsPerMask() : 0);
  if (masks != nullptr)
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gpu::kVisibilityMaskBinding, masks->masks());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gpu::kVplBinding, vpls.buffer.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gpu::kWorkListBinding, pyramid.workList());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gpu::kDispatchBinding, pyramid.dispatches());
  glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, pyramid.dispatches());
}

void HierarchicalGatherPass::runLevel(int level, const Pyramid& pyramid,
                                      const VisibilityMasks* masks) const {
  const GLuint inputs[] = {pyramid.positionDepth(level), pyramid.normal(level),
                           pyramid.specular(level)};
  glBindTextures(0, 3, inputs);
  glBindImageTexture(0, pyramid.diffuseResult(level), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
  glBindImageTexture(1, pyramid.specularResult(level), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
  gl::setUniform(program_, "level", level);
  gl::setUniform(program_, "workListOffset", pyramid.workListOffset(level));
  gl::setUniform(program_, "maskOffset", masks != nullptr ? masks->maskOffset(level) : 0u);
  glDispatchComputeIndirect(static_cast<GLintptr>(level * sizeof(gpu::DispatchIndirect)));
}

void HierarchicalGatherPass::finish() const {
  glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, 0);
  glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
}

}  // namespace penumbra
