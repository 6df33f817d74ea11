#pragma once
// Pass 3: refinement. From the coarsest level to full resolution, each texel is classified as
// computed here, covered by a coarser texel, refined further, unlit or invalid, and the
// computed ones are listed for an indirect gather dispatch per level.

#include <vector>

#include "gl/handles.h"
#include "gl/program.h"
#include "render/discontinuity.h"
#include "render/levels.h"
#include "render/scene_gpu.h"

namespace penumbra {

class VisibilityMasks;

struct RefinementThresholds {
  float depth = 0.0f;   // on the relative depth gradient (see discontinuity.comp)
  float normal = 0.0f;  // on the normal curvature |N1 - N2|
  // On a texel's extent over its distance to the nearest light (see discontinuity.comp).
  float lightProximity = 0.0f;
};

// What the refinement pass writes: each level's texel states (gpu::kTexel*), and the work
// lists, every level's computed texels one after the other (from layout().texelOffset), with
// one DispatchIndirect per level.
class RefinementState {
 public:
  explicit RefinementState(const LevelLayout& layout);

  const LevelLayout& layout() const { return layout_; }
  const gl::Texture& state(int level) const { return states_[static_cast<std::size_t>(level)]; }
  gl::Texture& state(int level) { return states_[static_cast<std::size_t>(level)]; }
  const gl::Buffer& workList() const { return workList_; }
  gl::Buffer& workList() { return workList_; }
  const gl::Buffer& dispatches() const { return dispatches_; }
  gl::Buffer& dispatches() { return dispatches_; }
  // Texels listed per level by the last run (reads the GPU's counters back).
  std::vector<unsigned> texelsPerLevel() const;

 private:
  LevelLayout layout_;
  std::vector<gl::Texture> states_;
  gl::Buffer workList_;
  gl::Buffer dispatches_;
};

// The program that turns work lists' counts into their indirect dispatches' arguments
// (worklist_args.comp), ready for linear work past GL's work-group limit (gl/dispatch.h).
gl::Program workListArgumentsProgram();

class RefinementPass {
 public:
  struct Inputs {
    const SceneGpu& scene;
    const ReducedGBuffer& reduced;
    // The level's visibility flags (the visibility pass runs first); nullptr without shadows, where
    // no change of visibility refines a texel.
    const VisibilityMasks* visibility;
    RefinementThresholds thresholds;
  };
  struct Outputs {
    RefinementState& refinement;
  };

  RefinementPass();
  // Classifies one level. Levels run from the coarsest, which starts the frame's work lists, to
  // level 0, which turns the lists' counts into indirect dispatch arguments.
  void runLevel(int level, const Inputs& in, const Outputs& out) const;

 private:
  gl::Program classify_;
  gl::Program classifyWithoutVisibility_;
  gl::Program dispatchArguments_;
};

}  // namespace penumbra
