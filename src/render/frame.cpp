#include "render/frame.h"

#include <algorithm>
#include <cmath>
#include <string>

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
  // Work-list entries pack x and y into 16 bits each.
  const int limitX = std::min({maxTexture, maxWidth, 65535});
  const int limitY = std::min({maxTexture, maxHeight, 65535});
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
    voxelGridBytes(settings.shadows.voxels);
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

unsigned FrameStatistics::samplesGathered() const {
  unsigned total = 0;
  for (const LevelStatistics& level : levels)
    total += level.samples;
  return total;
}

std::uint64_t FrameStatistics::shadowRays() const {
  std::uint64_t total = 0;
  for (const LevelStatistics& level : levels)
    total += level.shadowRays;
  return total;
}

bool isSharedPass(const std::string& pass) {
  return pass == "upload" || pass == "vpls" || pass == "gbuffer" || pass == "voxelize" ||
         pass == "bvh";
}

Renderer::Renderer(Scene& scene, glm::ivec2 size, TimingMethod timing)
    : camera_(cameraOfSize(scene.camera, checkedSize(size))),
      sceneGpu_(scene),
      gbuffer_(size),
      timer_(timing) {
  glTextureStorage2D(radiance_.id(), 1, GL_RGBA32F, size.x, size.y);
  glTextureStorage2D(indirect_.id(), 1, GL_RGBA32F, size.x, size.y);
}

void Renderer::render(int frame, const RenderSettings& settings,
                      std::optional<double> videoSeconds) {
  validate(settings);
  const ShadowSettings& shadows = settings.shadows;
  lastMode_ = settings.mode;
  lastShadows_ = shadows.enabled;
  lastBvh_ = shadows.visibility == ShadowSettings::Visibility::Bvh;
  timer_.startFrame();

  timer_.begin("upload");
  sceneGpu_.update(frame, videoSeconds.value_or(sceneTime(frame)),
                   cellsPerSideFor(settings.vplsPerLight));
  timer_.end();
  if (shadows.enabled && sceneGpu_.vplCount() > gpu::kMaxShadowedVpls) {
    throw RenderError("shadows support up to " + std::to_string(gpu::kMaxShadowedVpls) +
                      " VPLs in all (one bit each); this scene has " +
                      std::to_string(sceneGpu_.vplCount()) + ": lower --vpls");
  }

  timer_.begin("vpls");
  vplPass_.run(sceneGpu_, vpls_);
  timer_.end();

  timer_.begin("gbuffer");
  gbufferPass_.run(sceneGpu_, camera_, gbuffer_);
  timer_.end();

  ShadowRays shadowRays;
  if (shadows.enabled && shadows.visibility == ShadowSettings::Visibility::Bvh) {
    timer_.begin("bvh");
    bvh_.update(sceneGpu_, frame);
    timer_.end();
    shadowRays.bvh = &bvh_;
  } else if (shadows.enabled) {
    timer_.begin("voxelize");
    voxelizePass_.run(sceneGpu_, camera_, shadows.voxels, voxelGrid_);
    timer_.end();
    shadowRays.grid = &voxelGrid_;
  }
  const ShadowRays* rays = shadows.enabled ? &shadowRays : nullptr;

  if (settings.mode == RenderMode::Naive) {
    timer_.begin("gather");
    naiveGather_.run(gbuffer_, vpls_, camera_.position, rays, shadows.visibleFraction, radiance_);
    timer_.end();
    renderIndirect(settings, rays);
    passTimes_ = timer_.finishFrame();
    return;
  }

  const MultiresolutionSettings& multiresolution = settings.multiresolution;
  if (!pyramid_ || pyramid_->coarsestSize() != multiresolution.coarsestSize)
    pyramid_ = std::make_unique<Pyramid>(gbuffer_, multiresolution.coarsestSize);
  const Pyramid& pyramid = *pyramid_;

  timer_.begin("discontinuity");
  discontinuityPass_.run(gbuffer_, pyramid);
  timer_.end();

  // From the coarsest level to full resolution: visibility masks (traced or inherited), then
  // the classification that refines wherever depth, normals or visibility change.
  const RefinementThresholds thresholds{multiresolution.depthThreshold,
                                        multiresolution.normalThreshold};
  refinementPass_.begin(pyramid);
  if (shadows.enabled) {
    visibilityMasks_.prepare(pyramid, vpls_.count);
    visibilityPass_.begin(pyramid, visibilityMasks_);
  }
  for (int level = pyramid.levelCount() - 1; level >= 0; --level) {
    const std::string suffix = "/" + std::to_string(level);
    if (shadows.enabled) {
      timer_.begin("visibility" + suffix);
      visibilityPass_.runLevel(level, sceneGpu_, pyramid, visibilityMasks_, vpls_, shadowRays,
                               shadows.refinement);
      timer_.end();
    } else {
      const std::uint32_t noFlags = 0;
      glClearTexImage(pyramid.visibilityFlags(level), 0, GL_RED_INTEGER, GL_UNSIGNED_INT, &noFlags);
    }
    timer_.begin("refinement" + suffix);
    refinementPass_.classifyLevel(level, sceneGpu_, pyramid, thresholds);
    timer_.end();
  }
  refinementPass_.finish(pyramid);

  // Each level's gather timed apart, for bench's time per level.
  const VisibilityMasks* masks = shadows.enabled ? &visibilityMasks_ : nullptr;
  hierarchicalGather_.begin(pyramid, vpls_, camera_.position, masks, shadows.visibleFraction);
  for (int level = pyramid.levelCount() - 1; level >= 0; --level) {
    timer_.begin("gather/" + std::to_string(level));
    hierarchicalGather_.runLevel(level, pyramid, masks);
    timer_.end();
  }
  hierarchicalGather_.finish();

  timer_.begin("upsample");
  upsamplePass_.run(gbuffer_, pyramid, multiresolution.planeTolerance, radiance_);
  timer_.end();
  renderIndirect(settings, rays);
  passTimes_ = timer_.finishFrame();
}

void Renderer::renderIndirect(const RenderSettings& settings, const ShadowRays* rays) {
  const IndirectSettings& indirect = settings.indirect;
  if (!indirect.enabled) {
    const glm::vec4 zero(0.0f);
    glClearTexImage(indirect_.id(), 0, GL_RGBA, GL_FLOAT, &zero[0]);
    return;
  }
  timer_.begin("bounce rsm");
  if (!rsm_ || rsm_->faceSize() != indirect.rsmSize || rsm_->lightCount() != sceneGpu_.lightCount())
    rsm_ = std::make_unique<ReflectiveShadowMap>(indirect.rsmSize, sceneGpu_.lightCount());
  rsmPass_.run(sceneGpu_, vpls_, *rsm_);
  timer_.end();

  timer_.begin("bounce vpls");
  const ReflectiveShadowMap::Texels texels = rsm_->read();
  uploadVpls(sampleSecondaryVpls(texels.positionArea, texels.normal, texels.radiance,
                                 indirect.vplCount, indirect.rsmSize),
             secondaryVpls_);
  timer_.end();

  // Visibility from the light needs the BVH or a grid over the world: the screen grid only
  // covers the camera's frustum, so with it the secondary VPLs stay unshadowed.
  if (rays != nullptr &&
      (rays->bvh != nullptr || settings.shadows.voxels.grid == VoxelSettings::Grid::World)) {
    timer_.begin("bounce shadows");
    secondaryVisibility_.run(vpls_, sceneGpu_.cellsPerSide() * sceneGpu_.cellsPerSide(), *rays,
                             secondaryVpls_);
    timer_.end();
  }

  timer_.begin("bounce gather");
  if (settings.mode == RenderMode::Naive || !pyramid_) {
    indirectGather_.run(gbuffer_, nullptr, 0, secondaryVpls_, indirect.planeTolerance, radiance_,
                        indirect_);
  } else {
    const int level =
        std::min(levelCountFor(gbuffer_.size, indirect.gatherSize), pyramid_->levelCount()) - 1;
    indirectGather_.run(gbuffer_, pyramid_.get(), level, secondaryVpls_, indirect.planeTolerance,
                        radiance_, indirect_);
  }
  timer_.end();
}

void Renderer::setCamera(const Camera& camera) {
  camera_ = cameraOfSize(camera, gbuffer_.size);
}

Image Renderer::readRadiance() const {
  return readTexture(radiance_.id(), gbuffer_.size);
}

FrameStatistics Renderer::statistics() const {
  FrameStatistics statistics;
  const Image normals = readTexture(gbuffer_.normalKind.id(), gbuffer_.size);
  for (const glm::vec4& normal : normals.pixels)
    if (static_cast<int>(normal.w) == gpu::kPixelSurface)
      ++statistics.fullResolutionSamples;
  if (lastShadows_) {
    statistics.vplCount = vpls_.count;
    statistics.visibilityBytes =
        lastBvh_ ? bvh_.bytes()
                 : voxelGrid_.wordCount * sizeof(std::uint32_t) + sizeof(gpu::GpuVoxelGrid);
  }
  if (lastMode_ == RenderMode::Hierarchical && pyramid_) {
    const std::vector<unsigned> counts = texelsPerLevel(*pyramid_);
    const std::vector<VisibilityWork> visibility =
        lastShadows_ ? visibilityPass_.workPerLevel(*pyramid_, visibilityMasks_)
                     : std::vector<VisibilityWork>(counts.size());
    for (int level = 0; level < pyramid_->levelCount(); ++level) {
      const auto index = static_cast<std::size_t>(level);
      statistics.levels.push_back({pyramid_->size(level), counts[index],
                                   visibility[index].tracedTexels, visibility[index].shadowRays});
    }
  }
  return statistics;
}

Image readTexels(GLuint texture, glm::ivec2 size) {
  Image image(size.x, size.y);
  glGetTextureImage(texture, 0, GL_RGBA, GL_FLOAT,
                    static_cast<GLsizei>(image.pixels.size() * sizeof(glm::vec4)),
                    image.pixels.data());
  return image;
}

Image readTexture(GLuint texture, glm::ivec2 size) {
  const Image texels = readTexels(texture, size);
  Image image(size.x, size.y);
  // GL's row 0 is the bottom of the picture.
  for (int y = 0; y < size.y; ++y) {
    std::copy_n(texels.pixels.begin() + static_cast<std::ptrdiff_t>(size.y - 1 - y) * size.x,
                size.x, image.pixels.begin() + static_cast<std::ptrdiff_t>(y) * size.x);
  }
  return image;
}

}  // namespace penumbra
