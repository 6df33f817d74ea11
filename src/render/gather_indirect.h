#pragma once
// Indirect light, pass 3: the gather of the secondary VPLs. Indirect light is smooth, so it is
// gathered at one coarser level of the pyramid (its own size setting), then brought to full
// resolution by a bilinear upsampling weighted by agreement of position and normal; a pixel
// whose agreeing coarse texels carry too little weight (edges, thin features) is gathered
// exactly. At the coarser level each 2x2 block of texels shares out the secondary VPLs (one
// subset each, interleaved sampling: secondary_gather.glsl), and a filter over the level
// (indirect_filter.comp) then gives every texel all four subsets before the upsampling; the
// exactly gathered pixels take their subset by their own parity. In naive mode every pixel
// gathers every secondary VPL at full resolution. With shadow rays the secondary VPLs are
// shadowed on their way to the receivers, in batches of the device profile's rays per dispatch:
// through the exact hierarchy (--visibility bvh) each VPL; through the voxel grid each cluster
// of VPLs, whose rays the texels of a subset on one surface in a workgroup share out, and there
// the pixels gathered exactly stay unshadowed (gather_indirect.comp, secondary_gather.glsl).

#include "gl/handles.h"
#include "gl/program.h"
#include "render/discontinuity.h"
#include "render/gbuffer.h"
#include "render/shadow_rays.h"
#include "render/vpls.h"

namespace penumbra {

class IndirectGatherPass {
 public:
  struct Inputs {
    const GBuffer& gbuffer;
    // Null: gather at full resolution; otherwise at `level` of it.
    const ReducedGBuffer* reduced = nullptr;
    int level = 0;
    const VplBuffer& vpls;  // the secondary VPLs
    float planeTolerance = 0.0f;
    // Shadows the bounce's second leg; null: unshadowed.
    const ShadowRays* rays = nullptr;
  };
  struct Outputs {
    // Both RGBA32F of the G-buffer's size: the indirect light is added to `radiance` and written
    // alone to `indirect` (w: 1 where a pixel was gathered exactly).
    gl::Texture& radiance;
    gl::Texture& indirect;
  };

  // shadowRaysPerDispatch: the device profile's VPL batch with shadows (device_profile.h).
  explicit IndirectGatherPass(int shadowRaysPerDispatch);
  // Not const: the pass keeps its irradiance texture of the gather level's size.
  void run(const Inputs& in, const Outputs& out);

 private:
  ShadowRayProgram gather_;
  gl::Program unshadowedGather_;
  gl::Program filter_;
  // Its exact pixels trace shadow rays only through the BVH.
  ShadowRayProgram combine_;
  int shadowRaysPerDispatch_;
  glm::ivec2 irradianceSize_{0};
  gl::Texture irradiance_{GL_TEXTURE_2D};
  gl::Texture filtered_{GL_TEXTURE_2D};  // irradiance_ after indirect_filter.comp
};

}  // namespace penumbra
