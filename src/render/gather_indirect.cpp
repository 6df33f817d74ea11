#include "render/gather_indirect.h"

#include <algorithm>

#include "gl/dispatch.h"
#include "gl/uniforms.h"
#include "render/bindings.h"
#include "shared.h"

namespace penumbra {

IndirectGatherPass::IndirectGatherPass(int shadowRaysPerDispatch)
    : gather_("gather_indirect.comp"),
      unshadowedGather_(
          gl::Program::compute("gather_indirect.comp", {"PENUMBRA_UNSHADOWED_SECOND_LEG"})),
      filter_(gl::Program::compute("indirect_filter.comp")),
      combine_("indirect_combine.comp"),
      shadowRaysPerDispatch_(shadowRaysPerDispatch) {}

void IndirectGatherPass::run(const Inputs& in, const Outputs& out) {
  const GBuffer& gbuffer = in.gbuffer;
  const VplBuffer& vpls = in.vpls;
  const int level = in.level;
  const bool fullResolution = in.reduced == nullptr || level == 0;
  const glm::ivec2 size = fullResolution ? gbuffer.size : in.reduced->layout().size(level);
  const gl::Texture& positionDepth =
      fullResolution ? gbuffer.positionDepth : in.reduced->positionDepth(level);
  const gl::Texture& normal = fullResolution ? gbuffer.normalKind : in.reduced->normal(level);
  if (size != irradianceSize_) {
    irradiance_ = gl::Texture(GL_TEXTURE_2D);
    glTextureStorage2D(irradiance_.id(), 1, GL_RGBA32F, size.x, size.y);
    filtered_ = gl::Texture(GL_TEXTURE_2D);
    glTextureStorage2D(filtered_.id(), 1, GL_RGBA32F, size.x, size.y);
    irradianceSize_ = size;
  }
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gpu::kVplBinding, vpls.buffer.id());

  if (in.rays != nullptr)
    in.rays->bind();
  // Interleaved only where the upsampling blends neighbouring texels (secondary_gather.glsl);
  // at full resolution every pixel gathers every VPL.
  const bool interleaved = !fullResolution && vpls.count >= gpu::kInterleavedSubsets;
  // Without shadow rays one dispatch gathers every VPL; with them, batches (gather_indirect.comp)
  // of the profile's rays per receiver through the BVH, which takes one VPL in
  // kInterleavedSubsets when interleaved; through the voxels, of kSecondaryClustersPerDispatch
  // clusters of kSecondaryVplsPerShadowRay VPLs per subset (secondary_gather.glsl), whose rays
  // the texels of a surface share out (fewer than the profile's rays on llvmpipe).
  const int allVpls = std::max(vpls.count, 1);
  const bool exactRays = in.rays != nullptr && in.rays->bvh != nullptr;
  const int subsets = interleaved ? gpu::kInterleavedSubsets : 1;
  const int batch =
      in.rays == nullptr ? allVpls
      : exactRays        ? shadowRaysPerDispatch_ * subsets
                  : gpu::kSecondaryClustersPerDispatch * subsets * gpu::kSecondaryVplsPerShadowRay;
  // Through the voxels the pixels gathered exactly keep the unshadowed leg: along the dragon's
  // many edges their rays cost three times those of the gather level at 1024x1024, and on the
  // Cornell boxes they hardly change the error, being few (docs/indirect.md).
  const ShadowRays* exactPixelRays = exactRays ? in.rays : nullptr;
  const auto setSubsets = [&](const gl::Program& program) {
    gl::setUniform(program, "secondaryVplCount", vpls.count);
    gl::setUniform(program, "interleaved", interleaved);
  };

  const gl::Program& gather = in.rays != nullptr ? gather_.forRays(*in.rays) : unshadowedGather_;
  gather.use();
  gl::setUniform(gather, "fullResolution", fullResolution);
  setSubsets(gather);
  bindSampledTextures({positionDepth, normal});
  bindImageForUpdating(0, irradiance_, GL_RGBA32F);
  dispatchInVplBatches(gather, size, vpls.count, batch);

  if (interleaved) {
    filter_.use();
    gl::setUniform(filter_, "planeTolerance", in.planeTolerance);
    bindSampledTextures({positionDepth, normal, irradiance_});
    bindImageForWriting(0, filtered_, GL_RGBA32F);
    gl::dispatchThreads(filter_, size);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
  }

  const gl::Program& combine = combine_.forRays(exactPixelRays);
  combine.use();
  gl::setUniform(combine, "scale", fullResolution ? 1 : 1 << level);
  gl::setUniform(combine, "planeTolerance", in.planeTolerance);
  setSubsets(combine);
  bindSampledTextures({gbuffer.positionDepth, gbuffer.normalKind, gbuffer.albedo, positionDepth,
                       normal, interleaved ? filtered_ : irradiance_});
  bindImageForUpdating(0, out.radiance, GL_RGBA32F);
  bindImageForUpdating(1, out.indirect, GL_RGBA32F);
  // At full resolution no pixel gathers exactly: one dispatch takes the gathered irradiance.
  dispatchInVplBatches(combine, gbuffer.size, vpls.count,
                       fullResolution || exactPixelRays == nullptr ? allVpls : batch);
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT);
}

}  // namespace penumbra
