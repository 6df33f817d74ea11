#include "render/frame.h"

#include <algorithm>
#include <cmath>
#include <string>

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
    throw RenderError("image size " + std::to_string(size.x) + "x" + std::to_string(size.y) +
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
}

unsigned FrameStatistics::samplesGathered() const {
  unsigned total = 0;
  for (const LevelStatistics& level : levels)
    total += level.samples;
  return total;
}

bool isSharedPass(const std::string& pass) {
  return pass == "upload" || pass == "vpls" || pass == "gbuffer";
}

Renderer::Renderer(Scene& scene, glm::ivec2 size, TimingMethod timing)
    : camera_(cameraOfSize(scene.camera, checkedSize(size))),
      sceneGpu_(scene),
      gbuffer_(size),
      timer_(timing) {
  glTextureStorage2D(radiance_.id(), 1, GL_RGBA32F, size.x, size.y);
}

void Renderer::render(int frame, const RenderSettings& settings) {
  validate(settings);
  lastMode_ = settings.mode;
  timer_.startFrame();

  timer_.begin("upload");
  sceneGpu_.update(frame, cellsPerSideFor(settings.vplsPerLight));
  timer_.end();

  timer_.begin("vpls");
  vplPass_.run(sceneGpu_, vpls_);
  timer_.end();

  timer_.begin("gbuffer");
  gbufferPass_.run(sceneGpu_, camera_, gbuffer_);
  timer_.end();

  if (settings.mode == RenderMode::Naive) {
    timer_.begin("gather");
    naiveGather_.run(gbuffer_, vpls_, camera_.position, radiance_);
    timer_.end();
  } else {
    const MultiresolutionSettings& multiresolution = settings.multiresolution;
    if (!pyramid_ || pyramid_->coarsestSize() != multiresolution.coarsestSize)
      pyramid_ = std::make_unique<Pyramid>(gbuffer_, multiresolution.coarsestSize);

    timer_.begin("discontinuity");
    discontinuityPass_.run(gbuffer_, *pyramid_);
    timer_.end();

    timer_.begin("refinement");
    refinementPass_.run(sceneGpu_, *pyramid_,
                        {multiresolution.depthThreshold, multiresolution.normalThreshold});
    timer_.end();

    timer_.begin("gather");
    hierarchicalGather_.run(*pyramid_, vpls_, camera_.position);
    timer_.end();

    timer_.begin("upsample");
    upsamplePass_.run(gbuffer_, *pyramid_, multiresolution.planeTolerance, radiance_);
    timer_.end();
  }
  passTimes_ = timer_.finishFrame();
}

void Renderer::setCamera(const Camera& camera) { camera_ = cameraOfSize(camera, gbuffer_.size); }

Image Renderer::readRadiance() const {
  return readTexture(radiance_.id(), gbuffer_.size);
}

FrameStatistics Renderer::statistics() const {
  FrameStatistics statistics;
  const Image normals = readTexture(gbuffer_.normalKind.id(), gbuffer_.size);
  for (const glm::vec4& normal : normals.pixels)
    if (static_cast<int>(normal.w) == gpu::kPixelSurface)
      ++statistics.fullResolutionSamples;
  if (lastMode_ == RenderMode::Hierarchical && pyramid_) {
    const std::vector<unsigned> counts = texelsPerLevel(*pyramid_);
    for (int level = 0; level < pyramid_->levelCount(); ++level)
      statistics.levels.push_back({pyramid_->size(level), counts[static_cast<std::size_t>(level)]});
  }
  return statistics;
}

Image readTexture(GLuint texture, glm::ivec2 size) {
  std::vector<glm::vec4> rows(static_cast<std::size_t>(size.x) * size.y);
  glGetTextureImage(texture, 0, GL_RGBA, GL_FLOAT,
                    static_cast<GLsizei>(rows.size() * sizeof(glm::vec4)), rows.data());
  Image image(size.x, size.y);
  // GL's row 0 is the bottom of the picture.
  for (int y = 0; y < size.y; ++y) {
    std::copy_n(rows.begin() + static_cast<std::ptrdiff_t>(size.y - 1 - y) * size.x, size.x,
                image.pixels.begin() + static_cast<std::ptrdiff_t>(y) * size.x);
  }
  return image;
}

}  // namespace penumbra
