#include "render/gather_hierarchical.h"

#include <algorithm>

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

HierarchicalGatherPass::HierarchicalGatherPass(GatherVplSource preferred)
    : available_(gatherVplSourceOnThisContext(preferred)) {}

void HierarchicalGatherPass::runLevel(int level, const Inputs& in, const Outputs& out) {
  const VisibilityMasks* masks = in.visibility;
  const gpu::GpuVplRange everyVpl{glm::ivec4(0, in.vpls.count, -1, 0)};
  const std::span<const gpu::GpuVplRange> ranges =
      in.vplRanges.empty() ? std::span<const gpu::GpuVplRange>(&everyVpl, 1) : in.vplRanges;
  // Most frames ask for the same ranges at every level (those without a video light ask for one
  // set), so they are uploaded only when they change.
  const auto sameRange = [](const gpu::GpuVplRange& a, const gpu::GpuVplRange& b) {
    return a.range == b.range;
  };
  if (!std::equal(ranges.begin(), ranges.end(), uploadedRanges_.begin(), uploadedRanges_.end(),
                  sameRange)) {
    uploadedRanges_.assign(ranges.begin(), ranges.end());
    glNamedBufferData(vplRanges_.id(),
                      static_cast<GLsizeiptr>(ranges.size() * sizeof(gpu::GpuVplRange)),
                      ranges.data(), GL_DYNAMIC_DRAW);
  }
  const GatherVplSource source = gatherVplSource(in.vpls.count, available_);
  std::optional<gl::Program>& compiled = programs_[static_cast<std::size_t>(source)];
  if (!compiled)
    compiled = gl::Program::compute("gather_hierarchical.comp", gatherVplDefines(source));
  const gl::Program& program = *compiled;
  program.use();
  gl::setUniform(program, "eyePosition", in.eyePosition);
  gl::setUniform(program, "vplCount", in.vpls.count);
  gl::setUniform(program, "vplRangeCount", static_cast<int>(ranges.size()));
  gl::setUniform(program, "addKept", in.kept != nullptr);
  gl::setUniform(program, "shadows", masks != nullptr);
  gl::setUniform(program, "visibleFraction", in.visibleFraction);
  gl::setUniform(program, "wordsPerMask", masks != nullptr ? masks->wordsPerMask() : 0);
  if (masks != nullptr)
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gpu::kVisibilityMaskBinding, masks->masks().id());
  bindGatherVpls(in.vpls, source);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gpu::kGatherVplRangeBinding, vplRanges_.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gpu::kLightBinding, in.lights);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gpu::kWorkListBinding, in.refinement.workList().id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gpu::kDispatchBinding,
                   in.refinement.dispatches().id());
  // Without kept sums the shader reads no kept texel, and the units hold an input of the level
  // (not the targets it writes).
  const gl::Texture& keptDiffuse =
      in.kept != nullptr ? in.kept->diffuse(level) : in.reduced.positionDepth(level);
  const gl::Texture& keptSpecular =
      in.kept != nullptr ? in.kept->specular(level) : in.reduced.positionDepth(level);
  bindSampledTextures({in.reduced.positionDepth(level), in.reduced.normal(level),
                       in.reduced.specular(level), keptDiffuse, keptSpecular});
  bindImageForWriting(0, out.gathered.diffuse(level), GL_RGBA32F);
  bindImageForWriting(1, out.gathered.specular(level), GL_RGBA32F);
  gl::setUniform(program, "level", level);
  gl::setUniform(program, "workListOffset", in.refinement.layout().texelOffset(level));
  gl::setUniform(program, "maskOffset", masks != nullptr ? masks->maskOffset(level) : 0u);
  glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, in.refinement.dispatches().id());
  glDispatchComputeIndirect(static_cast<GLintptr>(level * sizeof(gpu::DispatchIndirect)));
  glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, 0);
  glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
}

}  // namespace penumbra
