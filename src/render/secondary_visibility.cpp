#include "render/secondary_visibility.h"

#include <algorithm>

#include "gl/uniforms.h"
#include "shared.h"

namespace penumbra {

SecondaryVisibilityPass::SecondaryVisibilityPass(int shadowRaysPerDispatch)
    : program_("secondary_visibility.comp"), shadowRaysPerDispatch_(shadowRaysPerDispatch) {}

void SecondaryVisibilityPass::run(const Inputs& in, const Outputs& out) {
  const VplBuffer& vpls = in.vpls;
  const int vplsPerLight = in.vplsPerLight;
  const ShadowRays& rays = in.rays;
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
  const gl::Program& program = program_.forRays(rays);
  program.use();
  gl::setUniform(program, "secondaryCount", secondary.count);
  gl::setUniform(program, "vplsPerLight", vplsPerLight);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gpu::kVplBinding, vpls.buffer.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gpu::kSecondaryVplBinding, secondary.buffer.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gpu::kSecondarySumsBinding, sums_.id());
  rays.bind();
  const glm::uvec3 groups = program.groupsFor({static_cast<unsigned>(secondary.count), 1, 1});
  // Each secondary VPL traces a quarter of its light's VPLs (secondary_visibility.comp), so a
  // batch of four times the profile's rays gives each invocation the profile's share.
  const int batch = shadowRaysPerDispatch_ * gpu::kInterleavedSubsets;
  for (int first = 0; first < vplsPerLight; first += batch) {
    gl::setUniform(program, "firstVpl", first);
    gl::setUniform(program, "endVpl", std::min(first + batch, vplsPerLight));
    glDispatchCompute(groups.x, groups.y, groups.z);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  }
}

}  // namespace penumbra
