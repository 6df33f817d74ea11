#pragma once
// Pass 4: the multiresolution gather. One indirect dispatch per level over its work list; each
// listed texel sums every VPL with the G-buffer averaged over its footprint.

#include "gl/program.h"
#include "render/pyramid.h"
#include "render/vpls.h"

namespace penumbra {

class HierarchicalGatherPass {
 public:
  HierarchicalGatherPass();
  void run(const Pyramid& pyramid, const VplBuffer& vpls, glm::vec3 eyePosition) const;

 private:
  gl::Program program_;
};

}  // namespace penumbra
