#include "render/shadow_rays.h"

#include <algorithm>
#include <utility>

#include "gl/uniforms.h"

#include "shared.h"

namespace penumbra {

void ShadowRays::bind() const {
  if (bvh != nullptr) {
    bvh->bind();
    return;
  }
  glBindBufferBase(GL_UNIFORM_BUFFER, gpu::kVoxelGridBinding, grid->header.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gpu::kVoxelBinding, grid->words.id());
}

ShadowRayProgram::ShadowRayProgram(std::string fileName, std::vector<std::string> defines)
    : fileName_(std::move(fileName)),
      defines_(std::move(defines)),
      defaultGrid_(compile("PENUMBRA_DEFAULT_VOXEL_GRID")) {}

gl::Program ShadowRayProgram::compile(const char* variantDefine) const {
  std::vector<std::string> defines = defines_;
  if (variantDefine != nullptr)
    defines.emplace_back(variantDefine);
  return gl::Program::compute(fileName_, defines);
}

const gl::Program& ShadowRayProgram::forRays(const ShadowRays& rays) const {
  if (rays.bvh != nullptr) {
    if (!bvh_)
      bvh_ = compile("PENUMBRA_BVH_VISIBILITY");
    return *bvh_;
  }
  if (isDefaultVoxelGrid(rays.grid->description))
    return defaultGrid_;
  if (!anyGrid_)
    anyGrid_ = compile(nullptr);
  return *anyGrid_;
}

bool isDefaultVoxelGrid(const gpu::GpuVoxelGrid& grid) {
  return grid.modes.x == gpu::kGridWorld && grid.modes.y == gpu::kTraversalDda &&
         grid.modes.w == 0 && grid.occupancy.y != 0;
}

void dispatchInVplBatches(const gl::Program& program, glm::ivec2 size, int vplCount, int batch) {
  const glm::uvec3 groups =
      program.groupsFor({static_cast<unsigned>(size.x), static_cast<unsigned>(size.y), 1});
  for (int first = 0; first < std::max(vplCount, 1); first += batch) {
    gl::setUniform(program, "firstVpl", first);
    gl::setUniform(program, "endVpl", std::min(first + batch, vplCount));
    glDispatchCompute(groups.x, groups.y, groups.z);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
  }
}

}  // namespace penumbra
