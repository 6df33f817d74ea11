#pragma once
// Pass 4: the multiresolution gather. One indirect dispatch per level over its work list; each
// listed texel sums every VPL with the G-buffer averaged over its footprint. The frame runs
// begin(), runLevel() for every level (timing each), then finish().

#include "gl/program.h"
#include "render/pyramid.h"
#include "render/visibility.h"
#include "render/vpls.h"

namespace penumbra {

class HierarchicalGatherPass {
 public:
  HierarchicalGatherPass();
  // `masks` null: every VPL is visible. visibleFraction: the thesis's shortcut.
  void begin(const Pyramid& pyramid, const VplBuffer& vpls, glm::vec3 eyePosition,
             const VisibilityMasks* masks, bool visibleFraction) const;
  // The same `masks` as begin().
  void runLevel(int level, const Pyramid& pyramid, const VisibilityMasks* masks) const;
  void finish() const;

 private:
  gl::Program program_;
};

}  // namespace penumbra
