#pragma once
// Pass: bitmask visibility (Schwarz & Stamminger), one bit per VPL per texel, computed level by
// level with the refinement: every lit texel at the coarsest level traces its mask; at a finer
// level, texels under a parent whose visibility differed from its neighbours' trace the VPLs on
// which the parent's neighbourhood disagrees and take the rest from the parent; the others
// inherit the parent's whole mask. Texels whose mask differs from a neighbour's are refined
// further. Through the BVH, or a world voxel grid with an occupancy pyramid, a listed texel first
// tests each quad light whole (the clear-light test, visibility_clear.comp) and traces no ray to a
// light it proves unoccluded. At full resolution a texel traces a quarter of those VPLs and takes
// the rest from its neighbours where they agree (visibility_share.comp, sibling_vpls.glsl).

#include <cstdint>
#include <vector>

#include "gl/handles.h"
#include "gl/program.h"
#include "render/discontinuity.h"
#include "render/levels.h"
#include "render/refinement.h"
#include "render/scene_gpu.h"
#include "render/shadow_rays.h"
#include "render/vpls.h"

namespace penumbra {

struct VisibilityRefinement {
  enum class Measure { XorPopcount, OccludedCountDifference };
  Measure measure = Measure::XorPopcount;
  float threshold = 0.0f;  // fraction of the VPL count; refine above it
  // At full resolution, a texel traces a quarter of the VPLs it would trace, those of its place
  // in its 2x2 block, and takes the others from its nearest neighbours at the other places where
  // they agree (sibling_vpls.glsl).
  bool shareVplsInBlocks = true;
  bool operator==(const VisibilityRefinement&) const = default;
};

// What the visibility pass did at each level in the last frame.
struct VisibilityWork {
  unsigned maskedTexels = 0;     // texels that hold a mask of their own (traced or inherited)
  unsigned tracedTexels = 0;     // those that traced (some of) it
  unsigned clearTexels = 0;      // listed texels that traced nothing: every light was clear
  std::uint64_t shadowRays = 0;  // VPLs they traced a ray to
};

// What the visibility pass writes: each level's flags (kVisibilityHasMask, kVisibilityChanges
// per texel), the masks of every level (dense, wordsPerMask words per texel), the list of texels
// to trace with its indirect dispatch per level, and the shadow rays traced per level.
class VisibilityMasks {
 public:
  explicit VisibilityMasks(const LevelLayout& layout);

  // (Re)allocates the masks for `vplCount` VPLs; throws RenderError above the memory limit.
  void prepare(int vplCount);
  // Zero flags at every level: a frame without shadows, whose refinement reads no change.
  void clearFlags();
  // Zero the counts of traced texels and shadow rays: the start of a frame's tracing, or a
  // frame that keeps the last frame's masks and traces nothing.
  void clearWork();

  const LevelLayout& layout() const { return layout_; }
  int vplCount() const { return vplCount_; }
  int wordsPerMask() const { return wordsPerMask_; }
  unsigned maskOffset(int level) const { return maskOffsets_[static_cast<std::size_t>(level)]; }
  const gl::Texture& flags(int level) const { return flags_[static_cast<std::size_t>(level)]; }
  gl::Texture& flags(int level) { return flags_[static_cast<std::size_t>(level)]; }
  const gl::Buffer& masks() const { return masks_; }
  gl::Buffer& masks() { return masks_; }
  gl::Buffer& traceList() { return traceList_; }
  const gl::Buffer& traceDispatches() const { return traceDispatches_; }
  gl::Buffer& traceDispatches() { return traceDispatches_; }
  gl::Buffer& shadowRayCounts() { return shadowRayCounts_; }
  gl::Buffer& clearLights() { return clearLights_; }
  gl::Buffer& givingNeighbours() { return givingNeighbours_; }

  // Per level, indexed from full resolution (reads the GPU's counters and flags back).
  std::vector<VisibilityWork> workPerLevel() const;

 private:
  LevelLayout layout_;
  int vplCount_ = 0;
  int wordsPerMask_ = 0;
  std::size_t allocatedWords_ = 0;
  std::vector<unsigned> maskOffsets_;
  std::vector<gl::Texture> flags_;
  gl::Buffer masks_;
  gl::Buffer traceList_;
  gl::Buffer traceDispatches_;
  gl::Buffer shadowRayCounts_;
  gl::Buffer clearLights_;       // per listed texel, the lights that passed the clear-light test
  gl::Buffer givingNeighbours_;  // per listed texel of the finest level (sibling_vpls.glsl)
};

// Shadow rays a trace dispatch lists (8 MiB): more than a dispatch of one mask word lists on the
// dragon at 1024x1024 (at most 957 thousand at its level 0, measured on 2026-12-06). Where the
// device profile allows few rays per dispatch (llvmpipe), a dispatch takes as many words as the
// list can hold rays for (VisibilityPass::traceWordsPerDispatch): on the demo at 512x512, all 16
// words of 512 VPLs at the coarsest level, 13, 6 and 4 at levels 2, 1 and 0.
inline constexpr unsigned kShadowRayListCapacity = 1u << 20;

class VisibilityPass {
 public:
  struct Inputs {
    const SceneGpu& scene;
    const ReducedGBuffer& reduced;
    const RefinementState& refinement;  // the parent level's states
    const VplBuffer& vpls;
    const ShadowRays& rays;
    // A texel takes visibility from its parent only where the parent's averaged point lies this
    // close to its tangent plane, as a fraction of its distance to the eye (and the normals
    // agree: parent_surface.glsl); the upsampling's tolerance (MultiresolutionSettings).
    float planeTolerance;
    VisibilityRefinement settings;
    // Test each quad light whole before tracing its VPLs (ShadowSettings::clearLightTest).
    bool clearLightTest = true;
  };
  struct Outputs {
    VisibilityMasks& visibility;  // prepared for the VPLs
  };

  // shadowRaysPerDispatch: the device profile's (device_profile.h), a multiple of 32 (a mask
  // word) or less. rayListCapacity: the shadow rays one trace dispatch lists to be traced one per
  // invocation (8 bytes each); the trace traces any more itself.
  explicit VisibilityPass(int shadowRaysPerDispatch,
                          unsigned rayListCapacity = kShadowRayListCapacity);
  // Masks and flags of one level. Levels run from the coarsest, which starts the frame's trace
  // lists and counters, to level 0; the parent level must be classified already.
  void runLevel(int level, const Inputs& in, const Outputs& out) const;

 private:
  // Mask words per trace dispatch at `level`, once its texels are listed.
  int traceWordsPerDispatch(const VisibilityMasks& visibility, int level) const;

  gl::Program select_;
  gl::Program dispatchArguments_;
  ShadowRayProgram clear_;
  ShadowRayProgram trace_;
  ShadowRayProgram rays_;
  ShadowRayProgram share_;
  gl::Program compare_;
  int shadowRaysPerDispatch_;
  unsigned rayListCapacity_;
  // The shadow rays of one trace dispatch (visibility_rays.comp), and their count and dispatch.
  gl::Buffer rayList_;
  gl::Buffer rayListDispatch_;
};

}  // namespace penumbra
