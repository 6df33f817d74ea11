#include "render/visibility.h"

#include <algorithm>
#include <cstdint>
#include <string>

#include "gl/dispatch.h"
#include "gl/uniforms.h"
#include "render/bindings.h"
#include "render/readback.h"
#include "render/render_error.h"
#include "shared.h"

namespace penumbra {

VisibilityMasks::VisibilityMasks(const LevelLayout& layout) : layout_(layout) {
  for (int level = 0; level < layout.levelCount(); ++level) {
    const glm::ivec2 size = layout.size(level);
    flags_.emplace_back(GL_TEXTURE_2D);
    glTextureStorage2D(flags(level).id(), 1, GL_R32UI, size.x, size.y);
  }
  glNamedBufferData(traceList_.id(), static_cast<GLsizeiptr>(layout.totalTexels()) * 4, nullptr,
                    GL_DYNAMIC_DRAW);
  glNamedBufferData(traceDispatches_.id(),
                    static_cast<GLsizeiptr>(gpu::kMaxLevels * sizeof(gpu::DispatchIndirect)),
                    nullptr, GL_DYNAMIC_DRAW);
  glNamedBufferData(shadowRayCounts_.id(),
                    static_cast<GLsizeiptr>(gpu::kMaxLevels * 3 * sizeof(std::uint32_t)), nullptr,
                    GL_DYNAMIC_DRAW);
  glNamedBufferData(clearLights_.id(), static_cast<GLsizeiptr>(layout.totalTexels()) * 4, nullptr,
                    GL_DYNAMIC_DRAW);
  glNamedBufferData(givingNeighbours_.id(),
                    static_cast<GLsizeiptr>(layout.size(0).x) * layout.size(0).y * 4, nullptr,
                    GL_DYNAMIC_DRAW);
}

void VisibilityMasks::prepare(int vplCount) {
  vplCount_ = vplCount;
  wordsPerMask_ = (vplCount + 31) / 32;
  maskOffsets_.clear();
  std::size_t words = 0;
  for (int level = 0; level < layout_.levelCount(); ++level) {
    maskOffsets_.push_back(static_cast<unsigned>(words));
    const glm::ivec2 size = layout_.size(level);
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
}

void VisibilityMasks::clearFlags() {
  const std::uint32_t noFlags = 0;
  for (gl::Texture& texture : flags_)
    glClearTexImage(texture.id(), 0, GL_RED_INTEGER, GL_UNSIGNED_INT, &noFlags);
}

void VisibilityMasks::clearWork() {
  const std::uint32_t zero = 0;
  glClearNamedBufferData(traceDispatches_.id(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
  glClearNamedBufferData(shadowRayCounts_.id(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
}

std::vector<VisibilityWork> VisibilityMasks::workPerLevel() const {
  const auto levels = static_cast<std::size_t>(layout_.levelCount());
  const auto dispatches = readBuffer<gpu::DispatchIndirect>(traceDispatches_.id(), 0, levels);
  const auto rayWords = readBuffer<std::uint32_t>(shadowRayCounts_.id(), 0, levels * 3);
  std::vector<VisibilityWork> work(levels);
  for (std::size_t level = 0; level < levels; ++level) {
    const glm::ivec2 size = layout_.size(static_cast<int>(level));
    for (const std::uint32_t flags :
         readUintTexture(flags_[level].id(), size, RowOrder::BottomFirst))
      if ((flags & gpu::kVisibilityHasMask) != 0)
        ++work[level].maskedTexels;
    work[level].clearTexels = rayWords[3 * level + 2];
    work[level].tracedTexels = dispatches[level].texelCount - work[level].clearTexels;
    work[level].shadowRays =
        rayWords[3 * level] | static_cast<std::uint64_t>(rayWords[3 * level + 1]) << 32;
  }
  return work;
}

VisibilityPass::VisibilityPass(int shadowRaysPerDispatch, unsigned rayListCapacity)
    : select_(gl::Program::compute("visibility_select.comp")),
      dispatchArguments_(workListArgumentsProgram()),
      clear_("visibility_clear.comp"),
      trace_("visibility_trace.comp"),
      rays_("visibility_rays.comp"),
      share_("visibility_share.comp"),
      compare_(gl::Program::compute("visibility_compare.comp")),
      shadowRaysPerDispatch_(shadowRaysPerDispatch),
      rayListCapacity_(rayListCapacity) {
  glNamedBufferData(rayList_.id(),
                    static_cast<GLsizeiptr>(std::max(rayListCapacity, 1u) * 2 * sizeof(GLuint)),
                    nullptr, GL_DYNAMIC_DRAW);
  glNamedBufferData(rayListDispatch_.id(), sizeof(gpu::DispatchIndirect), nullptr, GL_DYNAMIC_DRAW);
}

int VisibilityPass::traceWordsPerDispatch(const VisibilityMasks& visibility, int level) const {
  // As many mask words per dispatch as the device profile allows (visibility_trace.comp says
  // why): that many rays per invocation is what the trace may have to take on itself when the
  // ray list is full. A dispatch of more words is as safe while the list can hold every ray
  // the dispatch lists, at most 32 for each word of each listed texel; then the trace takes no
  // ray on itself. On llvmpipe (32 rays per dispatch) each dispatch costs a fixed time, about
  // 0.2 ms, and a trace over the texel list besides, which one dispatch per word paid 16 times a
  // level at 512 VPLs (docs/shadows.md).
  const int allowed = std::max(shadowRaysPerDispatch_ / 32, 1);
  const int words = visibility.wordsPerMask();
  if (allowed >= words)
    return allowed;
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  const std::uint32_t listed =
      readBuffer<gpu::DispatchIndirect>(visibility.traceDispatches().id(),
                                        static_cast<std::size_t>(level), 1)[0]
          .texelCount;
  const std::uint64_t raysPerWord = std::uint64_t{listed} * 32;
  if (raysPerWord == 0)
    return words;
  return static_cast<int>(
      std::clamp<std::uint64_t>(rayListCapacity_ / raysPerWord, allowed, words));
}

void VisibilityPass::runLevel(int level, const Inputs& in, const Outputs& out) const {
  VisibilityMasks& visibility = out.visibility;
  const LevelLayout& layout = visibility.layout();
  const bool hasParent = level < layout.coarsest();
  const int parent = hasParent ? level + 1 : level;
  const unsigned listOffset = layout.texelOffset(level);
  if (!hasParent)
    visibility.clearWork();
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gpu::kLightBinding, in.scene.lightBuffer());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gpu::kVplBinding, in.vpls.buffer.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gpu::kVisibilityMaskBinding, visibility.masks().id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gpu::kTraceListBinding, visibility.traceList().id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gpu::kTraceDispatchBinding,
                   visibility.traceDispatches().id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gpu::kShadowRayCountBinding,
                   visibility.shadowRayCounts().id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gpu::kClearLightBinding,
                   visibility.clearLights().id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gpu::kGivingNeighbourBinding,
                   visibility.givingNeighbours().id());
  in.rays.bind();
  bindSampledTextures({in.reduced.positionDepth(level), in.reduced.normal(level),
                       in.reduced.shadowLift(level), in.reduced.faceNormal(level),
                       in.reduced.positionDepth(parent), in.reduced.normal(parent)});

  // Select: trace, inherit, or nothing.
  bindImageForReading(0, in.refinement.state(parent), GL_R32UI);
  bindImageForReading(1, visibility.flags(parent), GL_R32UI);
  bindImageForWriting(2, visibility.flags(level), GL_R32UI);
  gl::setUniform(select_, "level", level);
  gl::setUniform(select_, "planeTolerance", in.planeTolerance);
  gl::setUniform(select_, "hasParent", hasParent);
  gl::setUniform(select_, "lightCount", in.scene.lightCount());
  gl::setUniform(select_, "wordsPerMask", visibility.wordsPerMask());
  gl::setUniform(select_, "maskOffset", visibility.maskOffset(level));
  gl::setUniform(select_, "parentMaskOffset", visibility.maskOffset(parent));
  gl::setUniform(select_, "traceListOffset", listOffset);
  gl::dispatchThreads(select_, layout.size(level));
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);

  // Trace the listed texels: an indirect dispatch sized by the select step's count.
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gpu::kDispatchBinding,
                   visibility.traceDispatches().id());
  gl::setUniform(dispatchArguments_, "levelCount", layout.levelCount());
  gl::setUniform(dispatchArguments_, "countLimit", ~0u);
  dispatchArguments_.use();
  glDispatchCompute(1, 1, 1);
  glMemoryBarrier(GL_COMMAND_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
  glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, visibility.traceDispatches().id());
  const GLintptr levelDispatch = static_cast<GLintptr>(level * sizeof(gpu::DispatchIndirect));

  // The clear-light test, one dispatch per quad light (the first kMaxClearLightTests), through
  // the BVH or where the grid has an occupancy pyramid: the world grid without --widen, whose
  // traversal tests only voxels its segment passes through (voxelize.cpp).
  const bool testClearLights =
      in.clearLightTest && (in.rays.bvh != nullptr || in.rays.grid->description.occupancy.x > 0);
  if (testClearLights) {
    const std::uint32_t noLights = 0;
    glClearNamedBufferSubData(
        visibility.clearLights().id(), GL_R32UI, listOffset * 4,
        static_cast<GLsizeiptr>(layout.size(level).x) * layout.size(level).y * 4, GL_RED_INTEGER,
        GL_UNSIGNED_INT, &noLights);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    const gl::Program& clear = clear_.forRays(in.rays);
    gl::setUniform(clear, "level", level);
    gl::setUniform(clear, "traceListOffset", listOffset);
    gl::setUniform(clear, "wordsPerMask", visibility.wordsPerMask());
    gl::setUniform(clear, "parentMaskOffset", visibility.maskOffset(parent));
    clear.use();
    const std::vector<Light>& lights = in.scene.scene().lights;
    for (int light = 0; light < std::min(in.scene.lightCount(), gpu::kMaxClearLightTests);
         ++light) {
      if (lights[static_cast<std::size_t>(light)].isMesh())
        continue;  // its VPLs are not in one quad
      gl::setUniform(clear, "lightIndex", light);
      glDispatchComputeIndirect(levelDispatch);
      glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    }
  }

  // At full resolution the texels of a block share out their VPLs; the trace and the share steps
  // read which texels hold masks.
  const bool shareVpls = level == 0 && in.settings.shareVplsInBlocks;
  bindImageForReading(2, visibility.flags(level), GL_R32UI);
  const gl::Program& trace = trace_.forRays(in.rays);
  gl::setUniform(trace, "shareVplsInBlocks", shareVpls);
  gl::setUniform(trace, "planeTolerance", in.planeTolerance);
  gl::setUniform(trace, "level", level);
  gl::setUniform(trace, "vplCount", in.vpls.count);
  gl::setUniform(trace, "wordsPerMask", visibility.wordsPerMask());
  gl::setUniform(trace, "maskOffset", visibility.maskOffset(level));
  gl::setUniform(trace, "parentMaskOffset", visibility.maskOffset(parent));
  gl::setUniform(trace, "traceListOffset", listOffset);
  gl::setUniform(trace, "lightCount", in.scene.lightCount());
  gl::setUniform(trace, "clearLightsTested", testClearLights);
  gl::setUniform(trace, "rayListCapacity", rayListCapacity_);
  const gl::Program& rays = rays_.forRays(in.rays);
  gl::setUniform(rays, "traceListOffset", listOffset);
  gl::setUniform(rays, "wordsPerMask", visibility.wordsPerMask());
  gl::setUniform(rays, "maskOffset", visibility.maskOffset(level));
  gl::setUniform(rays, "rayListCapacity", rayListCapacity_);
  // From here on the arguments program sizes the rays' dispatch.
  gl::setUniform(dispatchArguments_, "levelCount", 1);
  gl::setUniform(dispatchArguments_, "countLimit", rayListCapacity_);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gpu::kShadowRayListBinding, rayList_.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gpu::kShadowRayListDispatchBinding,
                   rayListDispatch_.id());
  const auto runOverListedTexels = [&](const gl::Program& program) {
    const std::uint32_t noRays = 0;
    glClearNamedBufferData(rayListDispatch_.id(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT,
                           &noRays);
    program.use();
    glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, visibility.traceDispatches().id());
    glDispatchComputeIndirect(levelDispatch);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  };
  const auto traceListedRays = [&] {
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gpu::kDispatchBinding, rayListDispatch_.id());
    dispatchArguments_.use();
    glDispatchCompute(1, 1, 1);
    glMemoryBarrier(GL_COMMAND_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
    rays.use();
    glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, rayListDispatch_.id());
    glDispatchComputeIndirect(0);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  };
  // Compiled only where a level shares out its VPLs (ShadowRayProgram compiles on first use).
  const gl::Program* share = shareVpls ? &share_.forRays(in.rays) : nullptr;
  if (share != nullptr) {
    gl::setUniform(*share, "shareVplsInBlocks", true);
    gl::setUniform(*share, "level", level);
    gl::setUniform(*share, "wordsPerMask", visibility.wordsPerMask());
    gl::setUniform(*share, "maskOffset", visibility.maskOffset(level));
    gl::setUniform(*share, "parentMaskOffset", visibility.maskOffset(parent));
    gl::setUniform(*share, "traceListOffset", listOffset);
    gl::setUniform(*share, "clearLightsTested", testClearLights);
    gl::setUniform(*share, "lightCount", in.scene.lightCount());
    gl::setUniform(*share, "vplCount", in.vpls.count);
    gl::setUniform(*share, "rayListCapacity", rayListCapacity_);
  }
  // Each dispatch lists its rays, then one invocation per listed ray traces them; at full
  // resolution the share step then lists the rays on which its texels' neighbours disagree.
  const int wordsPerDispatch = traceWordsPerDispatch(visibility, level);
  for (int word = 0; word < visibility.wordsPerMask(); word += wordsPerDispatch) {
    const int endWord = std::min(word + wordsPerDispatch, visibility.wordsPerMask());
    gl::setUniform(trace, "firstWord", word);
    gl::setUniform(trace, "endWord", endWord);
    runOverListedTexels(trace);
    traceListedRays();
    if (share != nullptr) {
      gl::setUniform(*share, "firstWord", word);
      gl::setUniform(*share, "endWord", endWord);
      runOverListedTexels(*share);
      traceListedRays();
    }
  }
  glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, 0);

  // Compare neighbours' masks.
  bindImageForUpdating(0, visibility.flags(level), GL_R32UI);
  gl::setUniform(compare_, "wordsPerMask", visibility.wordsPerMask());
  gl::setUniform(compare_, "maskOffset", visibility.maskOffset(level));
  gl::setUniform(compare_, "measure",
                 in.settings.measure == VisibilityRefinement::Measure::XorPopcount
                     ? gpu::kRefineByXorPopcount
                     : gpu::kRefineByOccludedCount);
  gl::setUniform(compare_, "threshold", in.settings.threshold * static_cast<float>(in.vpls.count));
  gl::dispatchThreads(compare_, layout.size(level));
  glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
}

}  // namespace penumbra
