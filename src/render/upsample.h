#pragma once
// Pass 5: upsample and combine, from the coarsest level to full resolution. A texel not
// computed at its level takes the valid texels of the coarser level, weighted by agreement of
// position and normal; at full resolution the albedo is applied and the emission added.

#include "gl/handles.h"
#include "gl/program.h"
#include "render/gbuffer.h"
#include "render/pyramid.h"

namespace penumbra {

class UpsamplePass {
 public:
  UpsamplePass();
  // planeTolerance: how far (as a fraction of the distance to the eye) a coarser texel may lie
  // off a texel's tangent plane and still be trusted.
  void run(const GBuffer& gbuffer, const Pyramid& pyramid, float planeTolerance,
           const gl::Texture& radiance) const;

 private:
  gl::Program program_;
};

}  // namespace penumbra
