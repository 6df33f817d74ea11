#include "render/gather_naive.h"

#include <algorithm>

#include "gl/uniforms.h"
#include "render/bindings.h"
#include "shared.h"

namespace penumbra {

NaiveGatherPass::NaiveGatherPass(int shadowRaysPerDispatch)
    : program_(gl::Program::compute("gather_naive.comp")),
      shadowRaysPerDispatch_(shadowRaysPerDispatch) {}

void NaiveGatherPass::run(const Inputs& in, const Outputs& out) const {
  const GBuffer& gbuffer = in.gbuffer;
  const VplBuffer& vpls = in.vpls;
  const VoxelGrid* grid = in.grid;
  program_.use();
  gl::setUniform(program_, "eyePosition", in.eyePosition);
  gl::setUniform(program_, "vplCount", vpls.count);
  gl::setUniform(program_, "shadows", grid != nullptr);
  gl::setUniform(program_, "visibleFraction", in.visibleFraction);
  if (grid != nullptr) {
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gpu::kVoxelGridBinding, grid->header.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gpu::kVoxelBinding, grid->words.id());
  }
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gpu::kVplBinding, vpls.buffer.id());
  bindSampledTextures({gbuffer.positionDepth, gbuffer.normalKind, gbuffer.albedo, gbuffer.specular,
                       gbuffer.emission});
  bindImageForUpdating(0, out.radiance, GL_RGBA32F);
  const glm::uvec3 groups = program_.groupsFor(
      {static_cast<unsigned>(gbuffer.size.x), static_cast<unsigned>(gbuffer.size.y), 1});
  // Without shadow rays one dispatch gathers every VPL; with them, batches (gather_naive.comp).
  const int batch = grid != nullptr ? shadowRaysPerDispatch_ : std::max(vpls.count, 1);
  for (int first = 0; first < std::max(vpls.count, 1); first += batch) {
    gl::setUniform(program_, "firstVpl", first);
    gl::setUniform(program_, "endVpl", std::min(first + batch, vpls.count));
    glDispatchCompute(groups.x, groups.y, groups.z);
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
  }
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT);
}

}  // namespace penumbra
