#include "render/shadow_rays.h"

#include <utility>

#include "shared.h"

namespace penumbra {

void ShadowRays::bind() const {
  if (bvh != nullptr) {
    bvh->bind();
    return;
  }
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gpu::kVoxelGridBinding, grid->header.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gpu::kVoxelBinding, grid->words.id());
}

ShadowRayProgram::ShadowRayProgram(std::string fileName)
    : fileName_(std::move(fileName)), voxels_(gl::Program::compute(fileName_)) {}

const gl::Program& ShadowRayProgram::forRays(const ShadowRays& rays) const {
  if (rays.bvh == nullptr)
    return voxels_;
  if (!bvh_)
    bvh_ = gl::Program::compute(fileName_, {"PENUMBRA_BVH_VISIBILITY"});
  return *bvh_;
}

}  // namespace penumbra
