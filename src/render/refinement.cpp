#include "render/refinement.h"

#include "gl/dispatch.h"
#include "gl/uniforms.h"
#include "render/bindings.h"
#include "render/readback.h"
#include "render/visibility.h"
#include "shared.h"

namespace penumbra {

RefinementState::RefinementState(const LevelLayout& layout) : layout_(layout) {
  for (int level = 0; level < layout.levelCount(); ++level) {
    const glm::ivec2 size = layout.size(level);
    states_.emplace_back(GL_TEXTURE_2D);
    glTextureStorage2D(state(level).id(), 1, GL_R32UI, size.x, size.y);
  }
  glNamedBufferData(workList_.id(),
                    static_cast<GLsizeiptr>(layout.totalTexels()) * sizeof(std::uint32_t), nullptr,
                    GL_DYNAMIC_DRAW);
  glNamedBufferData(dispatches_.id(),
                    static_cast<GLsizeiptr>(static_cast<std::size_t>(layout.levelCount()) *
                                            sizeof(gpu::DispatchIndirect)),
                    nullptr, GL_DYNAMIC_DRAW);
}

std::vector<unsigned> RefinementState::texelsPerLevel() const {
  const auto dispatches = readBuffer<gpu::DispatchIndirect>(
      dispatches_.id(), 0, static_cast<std::size_t>(layout_.levelCount()));
  std::vector<unsigned> counts;
  for (const gpu::DispatchIndirect& dispatch : dispatches)
    counts.push_back(dispatch.texelCount);
  return counts;
}

gl::Program workListArgumentsProgram() {
  gl::Program program = gl::Program::compute("worklist_args.comp");
  gl::setUniform(program, "maxGroupsPerDimension", gl::kMaxWorkGroupsPerDimension);
  return program;
}

RefinementPass::RefinementPass()
    : classify_(gl::Program::compute("refine_classify.comp")),
      classifyWithoutVisibility_(
          gl::Program::compute("refine_classify.comp", {"PENUMBRA_WITHOUT_VISIBILITY_FLAGS"})),
      dispatchArguments_(workListArgumentsProgram()) {}

void RefinementPass::runLevel(int level, const Inputs& in, const Outputs& out) const {
  RefinementState& refinement = out.refinement;
  const LevelLayout& layout = refinement.layout();
  const bool hasParent = level < layout.coarsest();
  if (!hasParent) {
    const std::uint32_t zero = 0;
    glClearNamedBufferData(refinement.dispatches().id(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT,
                           &zero);
  }
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gpu::kLightBinding, in.scene.lightBuffer());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gpu::kWorkListBinding, refinement.workList().id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gpu::kDispatchBinding, refinement.dispatches().id());
  const gl::Program& classify = in.visibility != nullptr ? classify_ : classifyWithoutVisibility_;
  gl::setUniform(classify, "depthThreshold", in.thresholds.depth);
  gl::setUniform(classify, "normalThreshold", in.thresholds.normal);
  gl::setUniform(classify, "lightProximityThreshold", in.thresholds.lightProximity);
  gl::setUniform(classify, "lightCount", in.scene.lightCount());
  bindSampledTextures(
      {in.reduced.positionDepth(level), in.reduced.normal(level), in.reduced.discontinuity(level)});
  // Without a parent the shader never reads unit 0; binding the level's own state keeps every
  // declared image bound.
  bindImageForReading(0, refinement.state(hasParent ? level + 1 : level), GL_R32UI);
  bindImageForWriting(1, refinement.state(level), GL_R32UI);
  if (in.visibility != nullptr)
    bindImageForReading(2, in.visibility->flags(level), GL_R32UI);
  gl::setUniform(classify, "level", level);
  gl::setUniform(classify, "hasParent", hasParent);
  gl::setUniform(classify, "workListOffset", layout.texelOffset(level));
  gl::dispatchThreads(classify, layout.size(level));
  glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
  if (level > 0)
    return;
  gl::setUniform(dispatchArguments_, "levelCount", layout.levelCount());
  gl::setUniform(dispatchArguments_, "countLimit", ~0u);
  dispatchArguments_.use();
  glDispatchCompute(1, 1, 1);
  glMemoryBarrier(GL_COMMAND_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
}

}  // namespace penumbra
