#pragma once
// Pass 5: upsample and combine, from the coarsest level to full resolution. A texel not
// computed at its level takes the valid texels of the coarser level, weighted by agreement of
// position and normal; at full resolution the albedo is applied and the emission added.

#include "gl/handles.h"
#include "gl/program.h"
#include "render/discontinuity.h"
#include "render/gather_hierarchical.h"
#include "render/gbuffer.h"
#include "render/refinement.h"

namespace penumbra {

class UpsamplePass {
 public:
  struct Inputs {
    const GBuffer& gbuffer;  // albedo and emission
    const ReducedGBuffer& reduced;
    const RefinementState& refinement;  // which texels were computed, covered or unlit
    // How far (as a fraction of the distance to the eye) a coarser texel may lie off a texel's
    // tangent plane and still be trusted.
    float planeTolerance = 0.0f;
  };
  struct Outputs {
    GatheredLevels& gathered;  // completed at every texel of every level
    gl::Texture& radiance;     // RGBA32F of the G-buffer's size
  };

  UpsamplePass();
  void run(const Inputs& in, const Outputs& out) const;

 private:
  gl::Program program_;
};

}  // namespace penumbra
