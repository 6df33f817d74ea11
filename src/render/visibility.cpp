#include "render/visibility.h"

#include <string>

#include "gl/dispatch.h"
#include "gl/uniforms.h"
#include "render/render_error.h"
#include "shared.h"

namespace penumbra {

void VisibilityMasks::prepare(const Pyramid& pyramid, int vplCount) {
  vplCount_ = vplCount;
  wordsPerMask_ = (vplCount + 31) / 32;
  maskOffsets_.clear();
  std::size_t words = 0;
  for (int level = 0; level < pyramid.levelCount(); ++level) {
    maskOffsets_.push_back(static_cast<unsigned>(words));
    const glm::ivec2 size = pyramid.size(level);
    words += static_cast<std::size_t>(size.x) * size.y * wordsPerMask_;
  }
  if (words * 4 > kMaxVoxelGridBytes) {
    throw RenderError("visibility masks for " + std::to_string(vplCount) + " VPLs need " +
                      std::to_string((words * 4) >> 20) + " MiB, more than the limit of " +
                      std::to_string(kMaxVoxelGridBytes >> 20) + " MiB");
  }
  if (words != allocatedWords_) {
    glNamedBufferData(masks_.id(), static_cast<GLsizeiptr>(std::max<std::size_t>(words, 1) * 4),
                      nullptr, GL_DYNAMIC_DRAW);
    allocatedWords_ = words;
  }
  if (pyramid.totalTexels() != allocatedTexels_) {
    glNamedBufferData(traceList_.id(), static_cast<GLsizeiptr>(pyramid.totalTexels()) * 4, nullptr,
                      GL_DYNAMIC_DRAW);
    glNamedBufferData(traceDispatches_.id(),
                      static_cast<GLsizeiptr>(gpu::kMaxLevels * sizeof(gpu::DispatchIndirect)),
                      nullptr, GL_DYNAMIC_DRAW);
    glNamedBufferData(shadowRayCounts_.id(),
                      static_cast<GLsizeiptr>(gpu::kMaxLevels * 2 * sizeof(std::uint32_t)), nullptr,
                      GL_DYNAMIC_DRAW);
    allocatedTexels_ = pyramid.totalTexels();
  }
}

VisibilityPass::VisibilityPass()
    : select_(gl::Program::compute("visibility_select.comp")),
      dispatchArguments_(gl::Program::compute("worklist_args.comp")),
      trace_("visibility_trace.comp"),
      compare_(gl::Program::compute("visibility_compare.comp")) {}

void VisibilityPass::begin(const Pyramid& pyramid, const VisibilityMasks& masks) const {
  const std::uint32_t zero = 0;
  glClearNamedBufferData(masks.traceDispatches(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
  glClearNamedBufferData(masks.shadowRayCounts(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
  gl::setUniform(dispatchArguments_, "levelCount", pyramid.levelCount());
}

void VisibilityPass::runLevel(int level, const SceneGpu& scene, const Pyramid& pyramid,
                              const VisibilityMasks& masks, const VplBuffer& vpls,
                              const ShadowRays& rays,
                              const VisibilityRefinement& refinement) const {
  const bool hasParent = level + 1 < pyramid.levelCount();
  const int parent = hasParent ? level + 1 : level;
  const unsigned listOffset = pyramid.workListOffset(level);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gpu::kLightBinding, scene.lightBuffer());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gpu::kVplBinding, vpls.buffer.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gpu::kVisibilityMaskBinding, masks.masks());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gpu::kTraceListBinding, masks.traceList());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gpu::kTraceDispatchBinding, masks.traceDispatches());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gpu::kShadowRayCountBinding, masks.shadowRayCounts());
  rays.bind();
  const GLuint inputs[] = {pyramid.positionDepth(level), pyramid.normal(level)};
  glBindTextures(0, 2, inputs);

  // Select: trace, inherit, or nothing.
  glBindImageTexture(0, pyramid.state(parent), 0, GL_FALSE, 0, GL_READ_ONLY, GL_R32UI);
  glBindImageTexture(1, pyramid.visibilityFlags(parent), 0, GL_FALSE, 0, GL_READ_ONLY, GL_R32UI);
  glBindImageTexture(2, pyramid.visibilityFlags(level), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32UI);
  gl::setUniform(select_, "level", level);
  gl::setUniform(select_, "hasParent", hasParent);
  gl::setUniform(select_, "lightCount", scene.lightCount());
  gl::setUniform(select_, "wordsPerMask", masks.wordsPerMask());
  glProgramUniform1ui(select_.id(), select_.uniform("maskOffset"), masks.maskOffset(level));
  glProgramUniform1ui(select_.id(), select_.uniform("parentMaskOffset"), masks.maskOffset(parent));
  glProgramUniform1ui(select_.id(), select_.uniform("traceListOffset"), listOffset);
  gl::dispatchThreads(select_, pyramid.size(level));
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);

  // Trace the listed texels: an indirect dispatch sized by the select step's count.
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gpu::kDispatchBinding, masks.traceDispatches());
  dispatchArguments_.use();
  glDispatchCompute(1, 1, 1);
  glMemoryBarrier(GL_COMMAND_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
  const gl::Program& trace = trace_.forRays(rays);
  gl::setUniform(trace, "level", level);
  gl::setUniform(trace, "hasParent", hasParent);
  gl::setUniform(trace, "vplCount", vpls.count);
  gl::setUniform(trace, "wordsPerMask", masks.wordsPerMask());
  glProgramUniform1ui(trace.id(), trace.uniform("maskOffset"), masks.maskOffset(level));
  glProgramUniform1ui(trace.id(), trace.uniform("parentMaskOffset"), masks.maskOffset(parent));
  glProgramUniform1ui(trace.id(), trace.uniform("traceListOffset"), listOffset);
  trace.use();
  glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, masks.traceDispatches());
  // One dispatch per mask word: visibility_trace.comp says why.
  for (int word = 0; word < masks.wordsPerMask(); ++word) {
    gl::setUniform(trace, "word", word);
    glDispatchComputeIndirect(static_cast<GLintptr>(level * sizeof(gpu::DispatchIndirect)));
  }
  glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, 0);
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);

  // Compare neighbours' masks.
  glBindImageTexture(0, pyramid.visibilityFlags(level), 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32UI);
  gl::setUniform(compare_, "wordsPerMask", masks.wordsPerMask());
  glProgramUniform1ui(compare_.id(), compare_.uniform("maskOffset"), masks.maskOffset(level));
  gl::setUniform(compare_, "measure",
                 refinement.measure == VisibilityRefinement::Measure::XorPopcount
                     ? gpu::kRefineByXorPopcount
                     : gpu::kRefineByOccludedCount);
  gl::setUniform(compare_, "threshold", refinement.threshold * static_cast<float>(vpls.count));
  gl::dispatchThreads(compare_, pyramid.size(level));
  glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
}

std::vector<VisibilityWork> VisibilityPass::workPerLevel(const Pyramid& pyramid,
                                                         const VisibilityMasks& masks) const {
  const auto levels = static_cast<std::size_t>(pyramid.levelCount());
  std::vector<gpu::DispatchIndirect> dispatches(levels);
  glGetNamedBufferSubData(masks.traceDispatches(), 0,
                          static_cast<GLsizeiptr>(dispatches.size() * sizeof(dispatches[0])),
                          dispatches.data());
  std::vector<std::uint32_t> rayWords(levels * 2);
  glGetNamedBufferSubData(masks.shadowRayCounts(), 0,
                          static_cast<GLsizeiptr>(rayWords.size() * sizeof(rayWords[0])),
                          rayWords.data());
  std::vector<VisibilityWork> work(levels);
  for (std::size_t level = 0; level < levels; ++level) {
    work[level].tracedTexels = dispatches[level].texelCount;
    work[level].shadowRays =
        rayWords[2 * level] | static_cast<std::uint64_t>(rayWords[2 * level + 1]) << 32;
  }
  return work;
}

}  // namespace penumbra
