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
  // shadowRaysPerDispatch: the device profile's VPL batch (device_profile.h).
  explicit SecondaryVisibilityPass(int shadowRaysPerDispatch);
  // `secondary`'s VPLs carry their light's index in normal.w; a world grid.
  void run(const VplBuffer& vpls, int vplsPerLight, const VoxelGrid& grid,
           const VplBuffer& secondary);

 private:
  gl::Program program_;
  gl::Buffer sums_;
  int sumsCapacity_ = 0;
  int shadowRaysPerDispatch_;
};

}  // namespace penumbra
