#include "render/gather_naive.h"

#include <algorithm>

#include "gl/uniforms.h"
#include "shared.h"

namespace penumbra {

NaiveGatherPass::NaiveGatherPass() : program_("gather_naive.comp") {}

void NaiveGatherPass::run(const GBuffer& gbuffer, const VplBuffer& vpls, glm::vec3 eyePosition,
                          const ShadowRays* rays, bool visibleFraction,
                          const gl::Texture& radiance) const {
  const gl::Program& program = rays != nullptr ? program_.forRays(*rays) : program_.voxels();
  program.use();
  gl::setUniform(program, "eyePosition", eyePosition);
  gl::setUniform(program, "vplCount", vpls.count);
  gl::setUniform(program, "shadows", rays != nullptr);
  gl::setUniform(program, "visibleFraction", visibleFraction);
  if (rays != nullptr)
    rays->bind();
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gpu::kVplBinding, vpls.buffer.id());
  const GLuint inputs[] = {gbuffer.positionDepth.id(), gbuffer.normalKind.id(), gbuffer.albedo.id(),
                           gbuffer.specular.id(), gbuffer.emission.id()};
  glBindTextures(0, 5, inputs);
  glBindImageTexture(0, radiance.id(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA32F);
  const glm::uvec3 groups = program.groupsFor(
      {static_cast<unsigned>(gbuffer.size.x), static_cast<unsigned>(gbuffer.size.y), 1});
  // Without shadow rays one dispatch gathers every VPL; with them, batches (gather_naive.comp).
  const int batch = rays != nullptr ? gpu::kShadowRaysPerDispatch : std::max(vpls.count, 1);
  for (int first = 0; first < std::max(vpls.count, 1); first += batch) {
    gl::setUniform(program, "firstVpl", first);
    gl::setUniform(program, "endVpl", std::min(first + batch, vpls.count));
    glDispatchCompute(groups.x, groups.y, groups.z);
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
  }
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT);
}

}  // namespace penumbra
