#pragma once
// The naive gather: every pixel sums every VPL at full resolution. The speed baseline and the
// accuracy target of the hierarchical gather.

#include <array>
#include <optional>

#include "gl/handles.h"
#include "gl/program.h"
#include "render/gbuffer.h"
#include "render/shadow_rays.h"
#include "render/vpls.h"

namespace penumbra {

class NaiveGatherPass {
 public:
  struct Inputs {
    const GBuffer& gbuffer;
    const VplBuffer& vpls;
    glm::vec3 eyePosition{0.0f};
    const ShadowRays* rays = nullptr;  // null: every VPL is visible; else a ray per pixel and VPL
    // The thesis's shortcut (unshadowed light times the visible fraction).
    bool visibleFraction = false;
  };
  struct Outputs {
    // The final radiance (emission, ambient and reflected light), RGBA32F of the G-buffer's size.
    gl::Texture& radiance;
  };

  // shadowRaysPerDispatch: the device profile's VPL batch with shadows (device_profile.h).
  // preferred: where the gather reads the VPLs when they fit in a uniform block
  // (gatherVplSource; the device profile's choice).
  NaiveGatherPass(int shadowRaysPerDispatch, GatherVplSource preferred);
  void run(const Inputs& in, const Outputs& out) const;

 private:
  int shadowRaysPerDispatch_;
  GatherVplSource available_;  // gatherVplSourceOnThisContext
  // The programs for each GatherVplSource, compiled on first use.
  mutable std::array<std::optional<ShadowRayProgram>, 2> programs_;
};

}  // namespace penumbra
