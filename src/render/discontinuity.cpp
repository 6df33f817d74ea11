#include "render/discontinuity.h"

#include <cassert>
#include <string>
#include <vector>

#include "gl/dispatch.h"
#include "gl/uniforms.h"
#include "render/bindings.h"
#include "shared.h"

namespace penumbra {

ReducedGBuffer::ReducedGBuffer(const GBuffer& gbuffer, const LevelLayout& layout)
    : gbuffer_(gbuffer), layout_(layout), levels_(static_cast<std::size_t>(layout.levelCount())) {
  for (int level = 0; level < layout.levelCount(); ++level) {
    const glm::ivec2 size = layout.size(level);
    Level& textures = at(level);
    if (level > 0) {
      for (const gl::Texture* texture :
           {&textures.positionDepth, &textures.normal, &textures.specular, &textures.shadowLift,
            &textures.faceNormal})
        glTextureStorage2D(texture->id(), 1, GL_RGBA32F, size.x, size.y);
    }
    glTextureStorage2D(textures.discontinuity.id(), 1, GL_RGBA32F, size.x, size.y);
  }
}

const gl::Texture& ReducedGBuffer::positionDepth(int level) const {
  return level == 0 ? gbuffer_.positionDepth : at(level).positionDepth;
}
const gl::Texture& ReducedGBuffer::normal(int level) const {
  return level == 0 ? gbuffer_.normalKind : at(level).normal;
}
const gl::Texture& ReducedGBuffer::specular(int level) const {
  return level == 0 ? gbuffer_.specular : at(level).specular;
}
const gl::Texture& ReducedGBuffer::shadowLift(int level) const {
  return level == 0 ? gbuffer_.shadowLift : at(level).shadowLift;
}
const gl::Texture& ReducedGBuffer::faceNormal(int level) const {
  return level == 0 ? gbuffer_.faceNormal : at(level).faceNormal;
}

ReducedGBuffer::Averages ReducedGBuffer::averages(int level) {
  assert(level > 0 && "level 0 is the G-buffer itself");
  Level& textures = at(level);
  return {textures.positionDepth, textures.normal, textures.specular, textures.shadowLift,
          textures.faceNormal};
}

DiscontinuityPass::Programs DiscontinuityPass::compilePrograms(bool shadowRayEnds) {
  std::vector<std::string> defines;
  if (!shadowRayEnds)
    defines.emplace_back("PENUMBRA_WITHOUT_SHADOW_RAY_ENDS");
  return {gl::Program::compute("discontinuity.comp", defines),
          gl::Program::compute("pyramid_reduce.comp", defines)};
}

DiscontinuityPass::DiscontinuityPass()
    : withShadowRayEnds_(compilePrograms(true)), withoutShadowRayEnds_(compilePrograms(false)) {}

namespace {

// The averages and discontinuity of one level above 0 at image units 0 to 5, where both programs
// write them (shaders/pyramid_footprint.glsl).
void bindLevelForWriting(ReducedGBuffer& reduced, int level) {
  const ReducedGBuffer::Averages averages = reduced.averages(level);
  bindImageForWriting(0, averages.positionDepth, GL_RGBA32F);
  bindImageForWriting(1, averages.normal, GL_RGBA32F);
  bindImageForWriting(2, averages.specular, GL_RGBA32F);
  bindImageForWriting(3, reduced.discontinuity(level), GL_RGBA32F);
  bindImageForWriting(4, averages.shadowLift, GL_RGBA32F);
  bindImageForWriting(5, averages.faceNormal, GL_RGBA32F);
}

}  // namespace

void DiscontinuityPass::run(const Inputs& in, const Outputs& out) const {
  const GBuffer& gbuffer = in.gbuffer;
  ReducedGBuffer& reduced = out.reduced;
  const int levelCount = reduced.layout().levelCount();
  const Programs& programs = in.shadowRayEnds ? withShadowRayEnds_ : withoutShadowRayEnds_;
  const gl::Program& firstTwoLevels = programs.firstTwoLevels;
  const gl::Program& coarserLevels = programs.coarserLevels;
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gpu::kLightBinding, in.scene.lightBuffer());
  gl::setUniform(firstTwoLevels, "lightCount", in.scene.lightCount());
  gl::setUniform(firstTwoLevels, "writesCoarser", levelCount > 1);
  bindSampledTextures({gbuffer.positionDepth, gbuffer.normalKind, gbuffer.specular,
                       gbuffer.shadowLift, gbuffer.faceNormal});
  bindImageForWriting(6, reduced.discontinuity(0), GL_RGBA32F);
  if (levelCount > 1) {
    bindLevelForWriting(reduced, 1);
  } else {
    // The shader writes no level 1 then, but every image unit it declares needs a texture.
    for (GLuint unit = 0; unit < 6; ++unit)
      bindImageForWriting(unit, reduced.discontinuity(0), GL_RGBA32F);
  }
  gl::dispatchThreads(firstTwoLevels, (gbuffer.size + 3) / 4);
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);

  for (int level = 2; level < levelCount; ++level) {
    const int finer = level - 1;
    bindSampledTextures({reduced.positionDepth(finer), reduced.normal(finer),
                         reduced.specular(finer), reduced.discontinuity(finer),
                         reduced.shadowLift(finer), reduced.faceNormal(finer)});
    bindLevelForWriting(reduced, level);
    gl::dispatchThreads(coarserLevels, reduced.layout().size(level));
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
  }
}

}  // namespace penumbra
