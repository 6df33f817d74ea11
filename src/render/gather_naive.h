#pragma once
// The naive gather: every pixel sums every VPL at full resolution. The speed baseline and the
// accuracy target of the hierarchical gather.

#include "gl/handles.h"
#include "gl/program.h"
#include "render/gbuffer.h"
#include "render/shadow_rays.h"
#include "render/vpls.h"

namespace penumbra {

class NaiveGatherPass {
 public:
  NaiveGatherPass();
  // Writes the final radiance (emission, ambient and reflected light) into `radiance`, an
  // RGBA32F texture of the G-buffer's size.
  // `rays` null: every VPL is visible; otherwise a shadow ray per pixel and VPL.
  // visibleFraction: the thesis's shortcut (unshadowed light times the visible fraction).
  void run(const GBuffer& gbuffer, const VplBuffer& vpls, glm::vec3 eyePosition,
           const ShadowRays* rays, bool visibleFraction, const gl::Texture& radiance) const;

 private:
  ShadowRayProgram program_;
};

}  // namespace penumbra
