#pragma once
// Pass 3: refinement. From the coarsest level to full resolution, each texel is classified as
// computed here, covered by a coarser texel, refined further, unlit or invalid, and the
// computed ones are listed for an indirect gather dispatch per level.

#include <vector>

#include "gl/program.h"
#include "render/pyramid.h"
#include "render/scene_gpu.h"

namespace penumbra {

struct RefinementThresholds {
  float depth = 0.0f;   // on the relative depth gradient (see discontinuity.comp)
  float normal = 0.0f;  // on the normal curvature |N1 - N2|
};

class RefinementPass {
 public:
  RefinementPass();
  // Clears the work lists; call once per frame before the levels.
  void begin(const Pyramid& pyramid) const;
  // Classifies one level; the parent level must be classified already. Reads the level's
  // visibility flags, so with shadows the visibility pass runs first.
  void classifyLevel(int level, const SceneGpu& scene, const Pyramid& pyramid,
                     const RefinementThresholds& thresholds) const;
  // Turns the work lists' counts into indirect dispatch arguments.
  void finish(const Pyramid& pyramid) const;

 private:
  gl::Program classify_;
  gl::Program dispatchArguments_;
};

// Texels listed per level by the last run (reads the GPU's counters back).
std::vector<unsigned> texelsPerLevel(const Pyramid& pyramid);

}  // namespace penumbra
