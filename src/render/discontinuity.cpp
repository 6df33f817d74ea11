#include "render/discontinuity.h"

#include <cassert>

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

DiscontinuityPass::DiscontinuityPass()
    : detect_(gl::Program::compute("discontinuity.comp")),
      reduce_(gl::Program::compute("pyramid_reduce.comp")) {}

void DiscontinuityPass::run(const Inputs& in, const Outputs& out) const {
  const GBuffer& gbuffer = in.gbuffer;
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gpu::kLightBinding, in.scene.lightBuffer());
  gl::setUniform(detect_, "lightCount", in.scene.lightCount());
  bindSampledTextures({gbuffer.positionDepth, gbuffer.normalKind, gbuffer.specular});
  bindImageForWriting(0, out.reduced.discontinuity(0), GL_RGBA32F);
  gl::dispatchThreads(detect_, gbuffer.size);
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);

  const ReducedGBuffer& finerLevels = out.reduced;
  for (int level = 1; level < finerLevels.layout().levelCount(); ++level) {
    const int finer = level - 1;
    bindSampledTextures({finerLevels.positionDepth(finer), finerLevels.normal(finer),
                         finerLevels.specular(finer), finerLevels.discontinuity(finer),
                         finerLevels.shadowLift(finer), finerLevels.faceNormal(finer)});
    const ReducedGBuffer::Averages averages = out.reduced.averages(level);
    bindImageForWriting(0, averages.positionDepth, GL_RGBA32F);
    bindImageForWriting(1, averages.normal, GL_RGBA32F);
    bindImageForWriting(2, averages.specular, GL_RGBA32F);
    bindImageForWriting(3, out.reduced.discontinuity(level), GL_RGBA32F);
    bindImageForWriting(4, averages.shadowLift, GL_RGBA32F);
    bindImageForWriting(5, averages.faceNormal, GL_RGBA32F);
    gl::setUniform(reduce_, "finerIsGBuffer", finer == 0);
    gl::setUniform(reduce_, "shadowRayEnds", in.shadowRayEnds);
    gl::dispatchThreads(reduce_, finerLevels.layout().size(level));
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
  }
}

}  // namespace penumbra
