#include "render/gather_hierarchical.h"

#include "gl/uniforms.h"
#include "render/bindings.h"
#include "shared.h"

namespace penumbra {

GatheredLevels::GatheredLevels(const LevelLayout& layout)
    : layout_(layout), levels_(static_cast<std::size_t>(layout.levelCount())) {
  for (int level = 0; level < layout.levelCount(); ++level) {
    const glm::ivec2 size = layout.size(level);
    glTextureStorage2D(diffuse(level).id(), 1, GL_RGBA32F, size.x, size.y);
    glTextureStorage2D(specular(level).id(), 1, GL_RGBA32F, size.x, size.y);
  }
}

HierarchicalGatherPass::HierarchicalGatherPass()
    : program_(gl::Program::compute("gather_hierarchical.comp")) {}

void HierarchicalGatherPass::runLevel(int level, const Inputs& in, const Outputs& out) const {
  const VisibilityMasks* masks = in.visibility;
  program_.use();
  gl::setUniform(program_, "eyePosition", in.eyePosition);
  gl::setUniform(program_, "vplCount", in.vpls.count);
  gl::setUniform(program_, "shadows", masks != nullptr);
  gl::setUniform(program_, "visibleFraction", in.visibleFraction);
  gl::setUniform(program_, "wordsPerMask", masks != nullptr ? masks->wordsPerMask() : 0);
  if (masks != nullptr)
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gpu::kVisibilityMaskBinding, masks->masks().id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gpu::kVplBinding, in.vpls.buffer.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gpu::kWorkListBinding, in.refinement.workList().id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gpu::kDispatchBinding,
                   in.refinement.dispatches().id());
  bindSampledTextures(
      {in.reduced.positionDepth(level), in.reduced.normal(level), in.reduced.specular(level)});
  bindImageForWriting(0, out.gathered.diffuse(level), GL_RGBA32F);
  bindImageForWriting(1, out.gathered.specular(level), GL_RGBA32F);
  gl::setUniform(program_, "level", level);
  gl::setUniform(program_, "workListOffset", in.refinement.layout().texelOffset(level));
  gl::setUniform(program_, "maskOffset", masks != nullptr ? masks->maskOffset(level) : 0u);
  glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, in.refinement.dispatches().id());
  glDispatchComputeIndirect(static_cast<GLintptr>(level * sizeof(gpu::DispatchIndirect)));
  glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, 0);
  glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
}

}  // namespace penumbra
