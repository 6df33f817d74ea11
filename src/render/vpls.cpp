#include "render/vpls.h"

#include <algorithm>
#include <cstddef>

#include "gl/uniforms.h"
#include "render/readback.h"
#include "shared.h"

namespace penumbra {

std::vector<gpu::GpuVpl> readVpls(const VplBuffer& source) {
  return readBuffer<gpu::GpuVpl>(source.buffer.id(), 0, static_cast<std::size_t>(source.count));
}

GatherVplSource gatherVplSourceOnThisContext(GatherVplSource preferred) {
  if (preferred != GatherVplSource::UniformBlock)
    return preferred;
  GLint largestBlock = 0;
  glGetIntegerv(GL_MAX_UNIFORM_BLOCK_SIZE, &largestBlock);
  return static_cast<std::size_t>(largestBlock) >= gpu::kVplsInUniformBlock * sizeof(gpu::GpuVpl)
             ? GatherVplSource::UniformBlock
             : GatherVplSource::StorageBuffer;
}

GatherVplSource gatherVplSource(int vplCount, GatherVplSource available) {
  return vplCount > gpu::kVplsInUniformBlock ? GatherVplSource::StorageBuffer : available;
}

std::vector<std::string> gatherVplDefines(GatherVplSource source) {
  if (source == GatherVplSource::StorageBuffer)
    return {"PENUMBRA_VPLS_IN_STORAGE_BUFFER"};
  return {};
}

void bindGatherVpls(const VplBuffer& vpls, GatherVplSource source) {
  if (source == GatherVplSource::StorageBuffer) {
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gpu::kVplBinding, vpls.buffer.id());
    return;
  }
  // The VPLs the buffer holds; the gather reads no others.
  glBindBufferRange(GL_UNIFORM_BUFFER, gpu::kVplUniformBlockBinding, vpls.buffer.id(), 0,
                    static_cast<GLsizeiptr>(std::max(vpls.count, 1) * sizeof(gpu::GpuVpl)));
}

VplPass::VplPass() : program_(gl::Program::compute("vpls.comp")) {}

void VplPass::run(const Inputs& in, const Outputs& out) const {
  const SceneGpu& scene = in.scene;
  VplBuffer& target = out.vpls;
  const int count = scene.vplCount();
  if (count != target.count) {
    glNamedBufferData(target.buffer.id(),
                      static_cast<GLsizeiptr>(std::max(count, 1)) * sizeof(gpu::GpuVpl), nullptr,
                      GL_DYNAMIC_DRAW);
    target.count = count;
  }
  program_.use();
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gpu::kLightBinding, scene.lightBuffer());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gpu::kVplBinding, target.buffer.id());
  const auto perLight = static_cast<unsigned>(scene.cellsPerSide() * scene.cellsPerSide());
  const glm::uvec3 groups = program_.groupsFor({perLight, 1, 1});
  for (int i = 0; i < scene.lightCount(); ++i) {
    const Light& light = scene.scene().lights[static_cast<std::size_t>(i)];
    if (light.isMesh()) {
      // Made on the CPU by SceneGpu::update: the cell partition of a mesh is no grid.
      std::vector<gpu::GpuVpl> vpls;
      for (const Vpl& vpl : scene.meshLightVpls(i))
        vpls.push_back({glm::vec4(vpl.position, vpl.area), glm::vec4(vpl.normal, 0.0f),
                        glm::vec4(vpl.radiance, 0.0f)});
      glNamedBufferSubData(target.buffer.id(),
                           static_cast<GLintptr>(i) * perLight * sizeof(gpu::GpuVpl),
                           static_cast<GLsizeiptr>(vpls.size() * sizeof(gpu::GpuVpl)), vpls.data());
      continue;
    }
    gl::setUniform(program_, "lightIndex", i);
    glBindTextureUnit(0, scene.texture(light.texture));
    glDispatchCompute(groups.x, groups.y, groups.z);
  }
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

}  // namespace penumbra
