#pragma once
// Indirect light, pass 2b (with shadows): each secondary VPL's radiance times the fraction of
// its light's irradiance that reaches it past the voxel grid (secondary_visibility.comp says
// why the maps themselves are lit without visibility).

#include "gl/handles.h"
#include "gl/program.h"
#include "render/voxelize.h"
#include "render/vpls.h"

namespace penumbra {

class SecondaryVisibilityPass {
 public:
  struct Inputs {
    const VplBuffer& vpls;  // the primary VPLs
    int vplsPerLight = 0;
    const VoxelGrid& grid;  // a world grid
  };
  struct Outputs {
    VplBuffer& secondary;  // their radiance is scaled; normal.w holds their light's index
  };

  // shadowRaysPerDispatch: the device profile's VPL batch (device_profile.h).
  explicit SecondaryVisibilityPass(int shadowRaysPerDispatch);
  // Not const: the pass keeps its buffer of per-VPL sums.
  void run(const Inputs& in, const Outputs& out);

 private:
  gl::Program program_;
  gl::Buffer sums_;
  int sumsCapacity_ = 0;
  int shadowRaysPerDispatch_;
};

}  // namespace penumbra
