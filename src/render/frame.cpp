#include "render/frame.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <span>
#include <string>
#include <utility>

#include "render/secondary_vpls.h"
#include "scene/transform.h"
#include "shared.h"

namespace penumbra {
namespace {

glm::ivec2 checkedSize(glm::ivec2 size) {
  GLint maxTexture = 0;
  GLint maxWidth = 0;
  GLint maxHeight = 0;
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxTexture);
  glGetIntegerv(GL_MAX_FRAMEBUFFER_WIDTH, &maxWidth);
  glGetIntegerv(GL_MAX_FRAMEBUFFER_HEIGHT, &maxHeight);
  // Work-list entries pack x and y into 16 bits each; trace-list entries keep y's top bit for a
  // flag (kTraceTexelParentStands).
  const int limitX = std::min({maxTexture, maxWidth, 65535});
  const int limitY = std::min({maxTexture, maxHeight, 32767});
  if (size.x < 1 || size.y < 1 || size.x > limitX || size.y > limitY) {
    throw GlLimitError("image size " + std::to_string(size.x) + "x" + std::to_string(size.y) +
                       " is outside what this GL implementation supports (1x1 to " +
                       std::to_string(limitX) + "x" + std::to_string(limitY) + ")");
  }
  return size;
}

Camera cameraOfSize(const Camera& camera, glm::ivec2 size) {
  Camera sized = camera;
  sized.size = size;
  return sized;
}

// The VPL range of each light (the gather leaves out a quad light that cannot light a texel), in
// the lights' order: all of them, those without a video, and the video lights.
struct LightVplRanges {
  std::vector<gpu::GpuVplRange> all;
  std::vector<gpu::GpuVplRange> steady;
  std::vector<gpu::GpuVplRange> varying;
};

LightVplRanges lightVplRanges(const Scene& scene, int vplsPerLight) {
  LightVplRanges ranges;
  for (std::size_t index = 0; index < scene.lights.size(); ++index) {
    const int light = static_cast<int>(index);
    const gpu::GpuVplRange range{
        glm::ivec4(light * vplsPerLight, (light + 1) * vplsPerLight, light, 0)};
    ranges.all.push_back(range);
    (radianceVaries(scene, scene.lights[index]) ? ranges.varying : ranges.steady).push_back(range);
  }
  return ranges;
}

}  // namespace

const char* renderModeName(RenderMode mode) {
  return mode == RenderMode::Hierarchical ? "hierarchical" : "naive";
}

int cellsPerSideFor(int vplsPerLight) {
  const int cells = static_cast<int>(std::lround(std::sqrt(static_cast<double>(vplsPerLight))));
  if (vplsPerLight < 1 || vplsPerLight > gpu::kMaxVplsPerLight || cells * cells != vplsPerLight) {
    throw RenderError("VPL count " + std::to_string(vplsPerLight) +
                      " is not a square number from 1 to " + std::to_string(gpu::kMaxVplsPerLight) +
                      " (e.g. 64, 256, 1024)");
  }
  return cells;
}

void validate(const RenderSettings& settings) {
  cellsPerSideFor(settings.vplsPerLight);
  if (settings.shadows.enabled) {
    // A cube's grid: the scene's box, known when it is voxelized, sets a cubic grid's shape.
    voxelGridBytes(settings.shadows.voxels, glm::vec3(1.0f));
    const float threshold = settings.shadows.refinement.threshold;
    if (!(threshold >= 0.0f) || threshold > 1.0f) {
      throw RenderError("visibility threshold " + std::to_string(threshold) +
                        " must be a fraction of the VPL count, from 0 to 1");
    }
  }
  const MultiresolutionSettings& multiresolution = settings.multiresolution;
  if (multiresolution.coarsestSize < 1) {
    throw RenderError("coarsest level size " + std::to_string(multiresolution.coarsestSize) +
                      " must be at least 1");
  }
  const auto checkPositive = [](float value, const char* name) {
    if (!(value > 0.0f) || !std::isfinite(value))
      throw RenderError(std::string(name) + " " + std::to_string(value) +
                        " must be a positive finite number");
  };
  checkPositive(multiresolution.depthThreshold, "depth threshold");
  checkPositive(multiresolution.normalThreshold, "normal threshold");
  checkPositive(multiresolution.planeTolerance, "plane tolerance");
  checkPositive(multiresolution.lightProximityThreshold, "light proximity threshold");
  const IndirectSettings& indirect = settings.indirect;
  if (indirect.enabled) {
    if (indirect.vplCount < 1 || indirect.vplCount > gpu::kMaxSecondaryVpls)
      throw RenderError("secondary VPL count " + std::to_string(indirect.vplCount) +
                        " must be from 1 to " + std::to_string(gpu::kMaxSecondaryVpls));
    if (indirect.rsmSize < 1 || indirect.rsmSize > 1024)
      throw RenderError("reflective shadow map size " + std::to_string(indirect.rsmSize) +
                        " must be from 1 to 1024");
    if (indirect.gatherSize < 1)
      throw RenderError("indirect gather size " + std::to_string(indirect.gatherSize) +
                        " must be at least 1");
    checkPositive(indirect.planeTolerance, "indirect plane tolerance");
  }
}

namespace {

// The sum over the levels of one of LevelStatistics' counts.
template <class Count>
Count sumOverLevels(const std::vector<LevelStatistics>& levels, Count LevelStatistics::*count) {
  Count total = 0;
  for (const LevelStatistics& level : levels)
    total += level.*count;
  return total;
}

}  // namespace

unsigned FrameStatistics::samplesGathered() const {
  return sumOverLevels(levels, &LevelStatistics::samples);
}

unsigned FrameStatistics::visibilityMasked() const {
  return sumOverLevels(levels, &LevelStatistics::visibilityMasked);
}

unsigned FrameStatistics::visibilityTraced() const {
  return sumOverLevels(levels, &LevelStatistics::visibilityTraced);
}

unsigned FrameStatistics::visibilityClear() const {
  return sumOverLevels(levels, &LevelStatistics::visibilityClear);
}

std::uint64_t FrameStatistics::shadowRays() const {
  return sumOverLevels(levels, &LevelStatistics::shadowRays);
}

HierarchyTargets::HierarchyTargets(const GBuffer& gbuffer, int coarsestSize)
    : layout(gbuffer.size, coarsestSize),
      reduced(gbuffer, layout),
      refinement(layout),
      visibility(layout),
      gathered(layout) {}

Renderer::Renderer(Scene& scene, glm::ivec2 size, const DeviceProfile& profile)
    : profile_(profile),
      camera_(cameraOfSize(scene.camera, checkedSize(size))),
      sceneGpu_(scene),
      gbuffer_(size),
      visibilityPass_(profile.shadowRaysPerDispatch),
      naiveGather_(profile.shadowRaysPerDispatch, profile.gatherVpls),
      hierarchicalGather_(profile.gatherVpls),
      secondaryVisibility_(profile.shadowRaysPerDispatch),
      indirectGather_(profile.shadowRaysPerDispatch),
      timer_(profile.timing) {
  glTextureStorage2D(radiance_.id(), 1, GL_RGBA32F, size.x, size.y);
  glTextureStorage2D(indirect_.id(), 1, GL_RGBA32F, size.x, size.y);
}

// The frame function: each pass's inputs (first braces) and outputs (second braces) show which
// pass's output feeds which.
void Renderer::render(int frame, const RenderSettings& settings,
                      std::optional<double> videoSeconds) {
  validate(settings);
  const ShadowSettings& shadows = settings.shadows;
  lastMode_ = settings.mode;
  lastShadows_ = shadows.enabled;
  lastBvh_ = shadows.visibility == ShadowSettings::Visibility::Bvh;
  // Only the hierarchical mode keeps its hierarchy (and, with shadows, masks); the naive one
  // traces inside its gather.
  std::optional<VisibilityReuseKey> key;
  if (settings.mode == RenderMode::Hierarchical)
    key = visibilityReuseKey(sceneGpu_.scene(), camera_, frame, settings);
  visibilityReused_ = settings.reuseVisibility && key && key == maskKey_;
  maskKey_.reset();
  const bool steadySumsKept = std::exchange(steadySumsKept_, false);
  vplsKept_ = 0;
  timer_.startFrame();
  {
    const auto timed = timer_.time(Stage::Upload);
    sceneGpu_.update(frame, videoSeconds.value_or(sceneTime(frame)),
                     cellsPerSideFor(settings.vplsPerLight));
  }
  checkShadowedVplCount(shadows.enabled);
  {
    const auto timed = timer_.time(Stage::Vpls);
    vplPass_.run({sceneGpu_}, {vpls_});
  }
  {
    const auto timed = timer_.time(Stage::GBuffer);
    (shadows.enabled ? gbufferPass_ : unshadowedGBufferPass_).run({sceneGpu_, camera_}, {gbuffer_});
  }
  ShadowRays shadowRays;
  structureKept_ = false;
  if (shadows.enabled) {
    VisibilityStructureKey structureKey =
        key ? key->structure : visibilityStructureKey(sceneGpu_.scene(), camera_, frame, shadows);
    structureKept_ = settings.reuseVisibility && structureKey == structureKey_;
    if (!structureKept_) {
      structureKey_.reset();
      if (lastBvh_) {
        const auto timed = timer_.time(Stage::Bvh);
        bvh_.update(sceneGpu_, frame);
      } else {
        const auto timed = timer_.time(Stage::Voxelize);
        voxelizePass_.run({sceneGpu_, camera_, shadows.voxels}, {voxelGrid_});
      }
      structureKey_ = std::move(structureKey);
    }
    if (lastBvh_)
      shadowRays.bvh = &bvh_;
    else
      shadowRays.grid = &voxelGrid_;
  }
  const ShadowRays* rays = shadows.enabled ? &shadowRays : nullptr;

  if (settings.mode == RenderMode::Naive) {
    {
      const auto timed = timer_.time(Stage::Gather);
      naiveGather_.run({gbuffer_, vpls_, camera_.position, rays, shadows.visibleFraction},
                       {radiance_});
    }
    renderIndirect(frame, settings, rays);
    stageTimes_ = timer_.finishFrame();
    return;
  }

  const MultiresolutionSettings& multiresolution = settings.multiresolution;
  HierarchyTargets& levels = hierarchyFor(multiresolution.coarsestSize);
  // A frame that reuses the hierarchy keeps the reduced G-buffer and the refinement (and, with
  // shadows, the masks): the key holds all they depend on (camera, transforms, light geometry,
  // settings; the pyramid reads the G-buffer's positions, normals and specular terms, never its
  // textured albedo or emission), so they are what this frame would compute.
  if (visibilityReused_) {
    levels.visibility.clearWork();
  } else {
    {
      const auto timed = timer_.time(Stage::Discontinuity);
      discontinuityPass_.run({gbuffer_, sceneGpu_, shadows.enabled}, {levels.reduced});
    }
    // From the coarsest level to full resolution: visibility masks (traced or inherited) from
    // the parent's states, then the classification that refines wherever depth, normals or
    // visibility change.
    if (shadows.enabled)
      levels.visibility.prepare(vpls_.count);
    else
      levels.visibility.clearFlags();
    const RefinementThresholds thresholds{multiresolution.depthThreshold,
                                          multiresolution.normalThreshold,
                                          multiresolution.lightProximityThreshold};
    for (int level = levels.layout.coarsest(); level >= 0; --level) {
      if (shadows.enabled) {
        const auto timed = timer_.time(Stage::Visibility, level);
        visibilityPass_.runLevel(
            level,
            {sceneGpu_, levels.reduced, levels.refinement, vpls_, shadowRays,
             multiresolution.planeTolerance, shadows.refinement, shadows.clearLightTest},
            {levels.visibility});
      }
      const auto timed = timer_.time(Stage::Refinement, level);
      refinementPass_.runLevel(
          level,
          {sceneGpu_, levels.reduced, shadows.enabled ? &levels.visibility : nullptr, thresholds},
          {levels.refinement});
    }
  }
  maskKey_ = std::move(key);
  // The last frame kept its steady lights' sums at the texels of the work lists this frame reuses
  // when it made those lists (their key holds the VPL count and visibleFraction).
  gatherHierarchy(settings, levels, visibilityReused_ && steadySumsKept);
  {
    const auto timed = timer_.time(Stage::Upsample);
    upsamplePass_.run({gbuffer_, levels.reduced, levels.refinement, multiresolution.planeTolerance},
                      {levels.gathered, radiance_});
  }
  lastPlaneTolerance_ = multiresolution.planeTolerance;
  fullResolutionCompleted_ = false;
  renderIndirect(frame, settings, rays);
  stageTimes_ = timer_.finishFrame();
}

const GatheredLevels& Renderer::completedGatheredLevels() const {
  assert(canCompleteGatheredLevels());
  HierarchyTargets& levels = *hierarchy_;
  if (!fullResolutionCompleted_) {
    upsamplePass_.completeFullResolution(
        {gbuffer_, levels.reduced, levels.refinement, lastPlaneTolerance_}, levels.gathered);
    fullResolutionCompleted_ = true;
  }
  return levels.gathered;
}

// The sums of the lights whose radiance cannot change while the hierarchy is reused (every light
// but the video lights) are gathered apart and kept: a frame that reuses the hierarchy (the camera
// and the scene still, a video playing) gathers only the video lights' VPLs and adds the kept
// sums, or nothing when no light has a video. Every frame sums the lights in the same order (the
// steady lights, then the others), so a frame that keeps the sums is the frame a fresh renderer
// makes, bit for bit. The visible fraction (with shadows) scales a texel's sum by its share of
// all the VPLs, so it gathers every light in every frame.
void Renderer::gatherHierarchy(const RenderSettings& settings, HierarchyTargets& levels,
                               bool steadySumsValid) {
  const ShadowSettings& shadows = settings.shadows;
  const VisibilityMasks* masks = shadows.enabled ? &levels.visibility : nullptr;
  const bool splitByRadiance = masks == nullptr || !shadows.visibleFraction;
  const LightVplRanges ranges = lightVplRanges(sceneGpu_.scene(), settings.vplsPerLight);
  const std::span<const gpu::GpuVplRange> steady =
      splitByRadiance ? std::span<const gpu::GpuVplRange>(ranges.steady)
                      : std::span<const gpu::GpuVplRange>();
  const std::span<const gpu::GpuVplRange> varying = ranges.varying;
  const bool split = !steady.empty() && !varying.empty();
  if (split && !levels.steadySums)
    levels.steadySums = std::make_unique<GatheredLevels>(levels.layout);
  if (steadySumsValid)
    for (const gpu::GpuVplRange& range : steady)
      vplsKept_ += range.range.y - range.range.x;
  if (steadySumsValid && varying.empty()) {
    steadySumsKept_ = true;  // the gathered levels hold this frame's sums already
    return;
  }
  // Each level's gather timed apart, for bench's time per level.
  for (int level = levels.layout.coarsest(); level >= 0; --level) {
    const auto timed = timer_.time(Stage::Gather, level);
    const HierarchicalGatherPass::Inputs every{.reduced = levels.reduced,
                                               .refinement = levels.refinement,
                                               .vpls = vpls_,
                                               .eyePosition = camera_.position,
                                               .visibility = masks,
                                               .visibleFraction = shadows.visibleFraction,
                                               .lights = sceneGpu_.lightBuffer(),
                                               .vplRanges = ranges.all,
                                               .kept = nullptr};
    if (!split) {
      hierarchicalGather_.runLevel(level, every, {levels.gathered});
      continue;
    }
    if (!steadySumsValid) {
      HierarchicalGatherPass::Inputs steadyLights = every;
      steadyLights.vplRanges = steady;
      hierarchicalGather_.runLevel(level, steadyLights, {*levels.steadySums});
    }
    HierarchicalGatherPass::Inputs varyingLights = every;
    varyingLights.vplRanges = varying;
    varyingLights.kept = levels.steadySums.get();
    hierarchicalGather_.runLevel(level, varyingLights, {levels.gathered});
  }
  steadySumsKept_ = splitByRadiance && !steady.empty();
}

HierarchyTargets& Renderer::hierarchyFor(int coarsestSize) {
  if (!hierarchy_ || hierarchy_->layout.coarsestSize() != coarsestSize)
    hierarchy_ = std::make_unique<HierarchyTargets>(gbuffer_, coarsestSize);
  return *hierarchy_;
}

void Renderer::checkShadowedVplCount(bool shadows) const {
  if (shadows && sceneGpu_.vplCount() > gpu::kMaxShadowedVpls) {
    throw RenderError("shadows support up to " + std::to_string(gpu::kMaxShadowedVpls) +
                      " VPLs in all (one bit each); this scene has " +
                      std::to_string(sceneGpu_.vplCount()) + ": lower --vpls");
  }
}

void Renderer::renderIndirect(int frame, const RenderSettings& settings, const ShadowRays* rays) {
  const IndirectSettings& indirect = settings.indirect;
  std::optional<BounceSourceKey> key;
  if (indirect.enabled)
    key = bounceSourceKey(sceneGpu_.scene(), camera_, frame, settings);
  bounceSourcesKept_ = settings.reuseVisibility && key && key == bounceSourceKey_;
  bounceSourceKey_.reset();
  if (!indirect.enabled) {
    const glm::vec4 zero(0.0f);
    glClearTexImage(indirect_.id(), 0, GL_RGBA, GL_FLOAT, &zero[0]);
    return;
  }
  // Both legs of the bounce need the BVH or a grid over the world: the screen grid only covers
  // the camera's frustum, so with it the bounce stays unshadowed.
  const ShadowRays* bounceRays =
      rays != nullptr &&
              (rays->bvh != nullptr || settings.shadows.voxels.grid == VoxelSettings::Grid::World)
          ? rays
          : nullptr;
  if (!bounceSourcesKept_)
    renderBounceSources(indirect, bounceRays);
  bounceSourceKey_ = std::move(key);

  const auto timed = timer_.time(Stage::BounceGather);
  const bool fullResolution = settings.mode == RenderMode::Naive || !hierarchy_;
  const ReducedGBuffer* reduced = fullResolution ? nullptr : &hierarchy_->reduced;
  const int level = fullResolution ? 0
                                   : std::min(levelCountFor(gbuffer_.size, indirect.gatherSize),
                                              hierarchy_->layout.levelCount()) -
                                         1;
  indirectGather_.run(
      {gbuffer_, reduced, level, secondaryVpls_, indirect.planeTolerance, bounceRays},
      {radiance_, indirect_});
}

void Renderer::renderBounceSources(const IndirectSettings& indirect, const ShadowRays* rays) {
  {
    const auto timed = timer_.time(Stage::BounceRsm);
    if (!rsm_ || rsm_->faceSize() != indirect.rsmSize ||
        rsm_->lightCount() != sceneGpu_.lightCount())
      rsm_ = std::make_unique<ReflectiveShadowMap>(indirect.rsmSize, sceneGpu_.lightCount());
    rsmPass_.run({sceneGpu_, vpls_}, {*rsm_});
  }
  {
    const auto timed = timer_.time(Stage::BounceVpls);
    const ReflectiveShadowMap::Texels texels = rsm_->read();
    uploadVpls(sampleSecondaryVpls(texels.positionArea, texels.normal, texels.radiance,
                                   indirect.vplCount, indirect.rsmSize),
               secondaryVpls_);
  }
  if (rays != nullptr) {
    const auto timed = timer_.time(Stage::BounceShadows);
    secondaryVisibility_.run({vpls_, sceneGpu_.cellsPerSide() * sceneGpu_.cellsPerSide(), *rays},
                             {secondaryVpls_});
  }
}

void Renderer::setCamera(const Camera& camera) {
  camera_ = cameraOfSize(camera, gbuffer_.size);
}

Image Renderer::readRadiance() const {
  return readTexture(radiance_.id(), gbuffer_.size, RowOrder::TopFirst);
}

FrameStatistics Renderer::statistics() const {
  FrameStatistics statistics;
  const Image normals = readTexture(gbuffer_.normalKind.id(), gbuffer_.size, RowOrder::BottomFirst);
  for (const glm::vec4& normal : normals.pixels)
    if (static_cast<int>(normal.w) == gpu::kPixelSurface)
      ++statistics.fullResolutionSamples;
  if (lastShadows_) {
    statistics.vplCount = vpls_.count;
    statistics.visibilityBytes =
        lastBvh_ ? bvh_.bytes()
                 : voxelGrid_.wordCount * sizeof(std::uint32_t) + sizeof(gpu::GpuVoxelGrid);
  }
  statistics.sceneUploadBytes = sceneGpu_.uploadedBytes();
  statistics.visibilityReused = visibilityReused_;
  statistics.visibilityStructureKept = structureKept_;
  statistics.vplsKept = vplsKept_;
  statistics.bounceSourcesKept = bounceSourcesKept_;
  if (lastMode_ == RenderMode::Hierarchical && hierarchy_) {
    const std::vector<unsigned> counts = hierarchy_->refinement.texelsPerLevel();
    const std::vector<VisibilityWork> visibility = lastShadows_
                                                       ? hierarchy_->visibility.workPerLevel()
                                                       : std::vector<VisibilityWork>(counts.size());
    for (int level = 0; level < hierarchy_->layout.levelCount(); ++level) {
      const auto index = static_cast<std::size_t>(level);
      statistics.levels.push_back({hierarchy_->layout.size(level), counts[index],
                                   visibility[index].maskedTexels, visibility[index].tracedTexels,
                                   visibility[index].shadowRays, visibility[index].clearTexels});
    }
  }
  return statistics;
}

}  // namespace penumbra
