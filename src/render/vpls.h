#pragma once
// Pass 0: light sampling. For every light, cellsPerSide^2 VPLs at the cell centres of its
// (u,v) grid, each with the exact mean radiance of its cell of the emission texture at the
// frame's time. Light l's VPLs are entries [l*N, (l+1)*N) of the buffer.

#include <string>
#include <vector>

#include "gl/handles.h"
#include "gl/program.h"
#include "render/scene_gpu.h"
#include "shared.h"

namespace penumbra {

struct VplBuffer {
  gl::Buffer buffer;
  int count = 0;
};

// The buffer's VPLs, read back.
std::vector<gpu::GpuVpl> readVpls(const VplBuffer& source);

// Where a gather reads the VPLs (shaders/gather_vpls.glsl says why a uniform block).
enum class GatherVplSource { UniformBlock, StorageBuffer };

// `preferred`, or the storage buffer where the current context's uniform blocks cannot hold
// gpu::kVplsInUniformBlock VPLs. A gather pass asks once, when it is made: the limit is the
// context's.
GatherVplSource gatherVplSourceOnThisContext(GatherVplSource preferred);
// Where a gather reads `vplCount` VPLs: from `available` (gatherVplSourceOnThisContext), or from
// the storage buffer where they do not fit in the uniform block.
GatherVplSource gatherVplSource(int vplCount, GatherVplSource available);
// The defines that compile a gather for `source`.
std::vector<std::string> gatherVplDefines(GatherVplSource source);
// Binds the VPLs where a gather compiled for `source` reads them.
void bindGatherVpls(const VplBuffer& vpls, GatherVplSource source);

class VplPass {
 public:
  struct Inputs {
    const SceneGpu& scene;  // the lights and their emission at the frame's time
  };
  struct Outputs {
    VplBuffer& vpls;
  };

  VplPass();
  void run(const Inputs& in, const Outputs& out) const;

 private:
  gl::Program program_;
};

}  // namespace penumbra
