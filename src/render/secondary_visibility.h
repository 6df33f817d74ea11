#pragma once
// Indirect light, pass 2b (with shadows): each secondary VPL's radiance times the fraction of
// its light's irradiance that reaches it past the voxel grid (secondary_visibility.comp says
// why the maps themselves are lit without visibility).

#include "gl/handles.h"
#include "gl/program.h"
#include "render/shadow_rays.h"
#include "render/vpls.h"

namespace penumbra {

class SecondaryVisibilityPass {
 public:
  SecondaryVisibilityPass();
  // `secondary`'s VPLs carry their light's index in normal.w; `rays` a world grid or the BVH.
  void run(const VplBuffer& vpls, int vplsPerLight, const ShadowRays& rays,
           const VplBuffer& secondary);

 private:
  ShadowRayProgram program_;
  gl::Buffer sums_;
  int sumsCapacity_ = 0;
};

}  // namespace penumbra
