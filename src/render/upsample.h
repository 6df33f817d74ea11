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
  // Every level from the coarsest: levels above 0 complete out.gathered, level 0 writes
  // out.radiance and leaves its covered and unlit texels out of out.gathered.
  void run(const Inputs& in, const Outputs& out) const;
  // After run, completes level 0 of `gathered` as run completes the others (for the debug views
  // that show it).
  void completeFullResolution(const Inputs& in, GatheredLevels& gathered) const;

 private:
  void runLevel(const gl::Program& program, int level, const Inputs& in,
                GatheredLevels& gathered) const;

  gl::Program levelProgram_;     // completes a level's results
  gl::Program radianceProgram_;  // level 0's radiance, without its results
};

}  // namespace penumbra
