#include "render/refinement.h"

#include "gl/dispatch.h"
#include "gl/uniforms.h"
#include "shared.h"

namespace penumbra {

RefinementPass::RefinementPass()
    : classify_(gl::Program::compute("refine_classify.comp")),
      dispatchArguments_(gl::Program::compute("worklist_args.comp")) {}

void RefinementPass::begin(const Pyramid& pyramid) const {
  const std::uint32_t zero = 0;
  glClearNamedBufferData(pyramid.dispatches(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
}

void RefinementPass::classifyLevel(int level, const SceneGpu& scene, const Pyramid& pyramid,
                                   const RefinementThresholds& thresholds) const {
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gpu::kLightBinding, scene.lightBuffer());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gpu::kWorkListBinding, pyramid.workList());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gpu::kDispatchBinding, pyramid.dispatches());
  gl::setUniform(classify_, "depthThreshold", thresholds.depth);
  gl::setUniform(classify_, "normalThreshold", thresholds.normal);
  gl::setUniform(classify_, "lightCount", scene.lightCount());
  const bool hasParent = level + 1 < pyramid.levelCount();
  const GLuint inputs[] = {pyramid.positionDepth(level), pyramid.normal(level),
                           pyramid.discontinuity(level)};
  glBindTextures(0, 3, inputs);
  // Without a parent the shader never reads unit 0; binding the level's own state keeps every
  // declared image bound.
  glBindImageTexture(0, pyramid.state(hasParent ? level + 1 : level), 0, GL_FALSE, 0, GL_READ_ONLY,
                     GL_R32UI);
  glBindImageTexture(1, pyramid.state(level), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32UI);
  glBindImageTexture(2, pyramid.visibilityFlags(level), 0, GL_FALSE, 0, GL_READ_ONLY, GL_R32UI);
  gl::setUniform(classify_, "level", level);
  gl::setUniform(classify_, "hasParent", hasParent);
  gl::setUniform(classify_, "workListOffset", pyramid.workListOffset(level));
  gl::dispatchThreads(classify_, pyramid.size(level));
  glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
}

void RefinementPass::finish(const Pyramid& pyramid) const {
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gpu::kDispatchBinding, pyramid.dispatches());
  gl::setUniform(dispatchArguments_, "levelCount", pyramid.levelCount());
  dispatchArguments_.use();
  glDispatchCompute(1, 1, 1);
  glMemoryBarrier(GL_COMMAND_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
}

std::vector<unsigned> texelsPerLevel(const Pyramid& pyramid) {
  std::vector<gpu::DispatchIndirect> dispatches(static_cast<std::size_t>(pyramid.levelCount()));
  glGetNamedBufferSubData(pyramid.dispatches(), 0,
                          static_cast<GLsizeiptr>(dispatches.size() * sizeof(dispatches[0])),
                          dispatches.data());
  std::vector<unsigned> counts;
  for (const gpu::DispatchIndirect& dispatch : dispatches)
    counts.push_back(dispatch.texelCount);
  return counts;
}

}  // namespace penumbra
