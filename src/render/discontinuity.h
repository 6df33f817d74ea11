#pragma once
// Pass 2: the discontinuity pyramid. Level 0 holds, per pixel, the relative depth gradient,
// the normal curvature and whether the pixel is a lit surface; every coarser level holds the
// maximum over its footprint, and the G-buffer averaged over the footprint's surface pixels.

#include "gl/program.h"
#include "render/gbuffer.h"
#include "render/pyramid.h"

namespace penumbra {

class DiscontinuityPass {
 public:
  DiscontinuityPass();
  void run(const GBuffer& gbuffer, const Pyramid& pyramid) const;

 private:
  gl::Program detect_;
  gl::Program reduce_;
};

}  // namespace penumbra
