#pragma once
// Indirect light, pass 2b (with shadows): each secondary VPL's radiance times the fraction of
// its light's irradiance that reaches it past the occluders (secondary_visibility.comp says
// why the maps themselves are lit without visibility).

#include "gl/handles.h"
#include "gl/program.h"
#include "render/shadow_rays.h"
#include "render/vpls.h"

namespace penumbra {

class SecondaryVisibilityPass {
 public:
  struct Inputs {
    const VplBuffer& vpls;  // the primary VPLs
    int vplsPerLight = 0;
    const ShadowRays& rays;  // a world grid or the BVH
  };
  struct Outputs {
    VplBuffer& secondary;  // their radiance is scaled; normal.w holds their light's index
  };

  // shadowRaysPerDispatch: the device profile's VPL batch (device_profile.h).
  explicit SecondaryVisibilityPass(int shadowRaysPerDispatch);
  // Not const: the pass keeps its buffer of per-VPL sums.
  void run(const Inputs& in, const Outputs& out);

 private:
  ShadowRayProgram program_;
  gl::Buffer sums_;
  int sumsCapacity_ = 0;
  int shadowRaysPerDispatch_;
};

}  // namespace penumbra
