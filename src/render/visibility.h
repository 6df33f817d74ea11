#pragma once
// Pass: bitmask visibility (Schwarz & Stamminger), one bit per VPL per texel, computed level by
// level with the refinement: every lit texel at the coarsest level traces its mask; at a finer
// level, texels under a parent whose visibility differed from its neighbours' trace the VPLs on
// which the parent's neighbourhood disagrees and take the rest from the parent; the others
// inherit the parent's whole mask. Texels whose mask differs from a neighbour's are refined
// further.

#include <cstdint>
#include <vector>

#include "gl/handles.h"
#include "gl/program.h"
#include "render/pyramid.h"
#include "render/scene_gpu.h"
#include "render/shadow_rays.h"
#include "render/vpls.h"

namespace penumbra {

struct VisibilityRefinement {
  enum class Measure { XorPopcount, OccludedCountDifference };
  Measure measure = Measure::XorPopcount;
  float threshold = 0.0f;  // fraction of the VPL count; refine above it
};

// Masks of every level (dense, wordsPerMask words per texel), the list of texels to trace and
// its indirect dispatch per level.
class VisibilityMasks {
 public:
  // (Re)allocates for `pyramid` and `vplCount` VPLs; throws RenderError above the memory limit.
  void prepare(const Pyramid& pyramid, int vplCount);
  int vplCount() const { return vplCount_; }
  int wordsPerMask() const { return wordsPerMask_; }
  unsigned maskOffset(int level) const { return maskOffsets_[static_cast<std::size_t>(level)]; }
  GLuint masks() const { return masks_.id(); }
  GLuint traceList() const { return traceList_.id(); }
  GLuint traceDispatches() const { return traceDispatches_.id(); }
  GLuint shadowRayCounts() const { return shadowRayCounts_.id(); }

 private:
  int vplCount_ = 0;
  int wordsPerMask_ = 0;
  std::size_t allocatedWords_ = 0;
  unsigned allocatedTexels_ = 0;
  std::vector<unsigned> maskOffsets_;
  gl::Buffer masks_;
  gl::Buffer traceList_;
  gl::Buffer traceDispatches_;
  gl::Buffer shadowRayCounts_;
};

// What the visibility pass did at each level in the last frame.
struct VisibilityWork {
  unsigned tracedTexels = 0;     // texels that traced (some of) their mask
  std::uint64_t shadowRays = 0;  // VPLs they traced a ray to
};

class VisibilityPass {
 public:
  VisibilityPass();
  // Clears the trace counters; call once per frame before the levels.
  void begin(const Pyramid& pyramid, const VisibilityMasks& masks) const;
  // Masks and visibility flags of one level; the parent level must be classified already.
  void runLevel(int level, const SceneGpu& scene, const Pyramid& pyramid,
                const VisibilityMasks& masks, const VplBuffer& vpls, const ShadowRays& rays,
                const VisibilityRefinement& refinement) const;
  // Per level, indexed from full resolution (reads the GPU's counters back).
  std::vector<VisibilityWork> workPerLevel(const Pyramid& pyramid,
                                           const VisibilityMasks& masks) const;

 private:
  gl::Program select_;
  gl::Program dispatchArguments_;
  ShadowRayProgram trace_;
  gl::Program compare_;
};

}  // namespace penumbra
