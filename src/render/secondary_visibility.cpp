#include "render/secondary_visibility.h"

#include <algorithm>

#include "gl/uniforms.h"
#include "shared.h"

namespace penumbra {

SecondaryVisibilityPass::SecondaryVisibilityPass(int shadowRaysPerDispatch)
    : program_(gl::Program::compute("secondary_visibility.comp")),
      shadowRaysPerDispatch_(shadowRaysPerDispatch) {}

void SecondaryVisibilityPass::run(const Inputs& in, const Outputs& out) {
  const VplBuffer& vpls = in.vpls;
  const int vplsPerLight = in.vplsPerLight;
  const VoxelGrid& grid = in.grid;
  VplBuffer& secondary = out.secondary;
  if (secondary.count == 0)
    return;
  if (secondary.count > sumsCapacity_) {
    glNamedBufferData(
        sums_.id(),
        static_cast<GLsizeiptr>(2 * secondary.count) * static_cast<GLsizeiptr>(sizeof(glm::vec4)),
        nullptr, GL_DYNAMIC_DRAW);
    sumsCapacity_ = secondary.count;
  }
  program_.use();
  gl::setUniform(program_, "secondaryCount", secondary.count);
  gl::setUniform(program_, "vplsPerLight", vplsPerLight);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gpu::kVplBinding, vpls.buffer.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gpu::kSecondaryVplBinding, secondary.buffer.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gpu::kSecondarySumsBinding, sums_.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gpu::kVoxelGridBinding, grid.header.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gpu::kVoxelBinding, grid.words.id());
  const glm::uvec3 groups = program_.groupsFor({static_cast<unsigned>(secondary.count), 1, 1});
  for (int first = 0; first < vplsPerLight; first += shadowRaysPerDispatch_) {
    gl::setUniform(program_, "firstVpl", first);
    gl::setUniform(program_, "endVpl", std::min(first + shadowRaysPerDispatch_, vplsPerLight));
    glDispatchCompute(groups.x, groups.y, groups.z);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  }
}

}  // namespace penumbra
