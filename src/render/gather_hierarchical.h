#pragma once
// Pass 4: the multiresolution gather. One indirect dispatch per level over its work list; each
// listed texel sums the VPLs of the given lights (every VPL by default) with the G-buffer averaged
// over its footprint, and adds the other lights' sums when it is given them.

#include <array>
#include <optional>
#include <span>
#include <vector>

#include "gl/handles.h"
#include "gl/program.h"
#include "render/discontinuity.h"
#include "render/levels.h"
#include "render/refinement.h"
#include "render/visibility.h"
#include "render/vpls.h"

namespace penumbra {

// What the gather writes at its listed texels and the upsampling completes: per level, the
// light before the albedo (w: 1 + the level it came from, negative where unlit, 0 for no value)
// and the specular reflection.
class GatheredLevels {
 public:
  explicit GatheredLevels(const LevelLayout& layout);

  const LevelLayout& layout() const { return layout_; }
  const gl::Texture& diffuse(int level) const { return at(level).diffuse; }
  gl::Texture& diffuse(int level) { return at(level).diffuse; }
  const gl::Texture& specular(int level) const { return at(level).specular; }
  gl::Texture& specular(int level) { return at(level).specular; }

 private:
  struct Level {
    gl::Texture diffuse{GL_TEXTURE_2D};
    gl::Texture specular{GL_TEXTURE_2D};
  };
  const Level& at(int level) const { return levels_[static_cast<std::size_t>(level)]; }
  Level& at(int level) { return levels_[static_cast<std::size_t>(level)]; }

  LevelLayout layout_;
  std::vector<Level> levels_;
};

class HierarchicalGatherPass {
 public:
  struct Inputs {
    const ReducedGBuffer& reduced;
    const RefinementState& refinement;  // the work lists
    const VplBuffer& vpls;
    glm::vec3 eyePosition{0.0f};
    const VisibilityMasks* visibility = nullptr;  // null: every VPL is visible
    bool visibleFraction = false;                 // the thesis's shortcut; needs every VPL
    GLuint lights = 0;  // the light list (SceneGpu::lightBuffer), which vplRanges index
    // The VPLs to sum, as the ranges of whole lights' VPL indices (z: the light, whose VPLs are
    // left out where it cannot light the texel); empty: every VPL, none left out.
    std::span<const gpu::GpuVplRange> vplRanges;
    // The other lights' sums at the same texels (an earlier run into other levels), added to
    // these; null: none.
    const GatheredLevels* kept = nullptr;
  };
  struct Outputs {
    GatheredLevels& gathered;
  };

  // preferred: where the gather reads the VPLs when they fit in a uniform block
  // (gatherVplSource; the device profile's choice).
  explicit HierarchicalGatherPass(GatherVplSource preferred);
  // Gathers the texels listed at `level`.
  void runLevel(int level, const Inputs& in, const Outputs& out);

 private:
  GatherVplSource available_;  // gatherVplSourceOnThisContext
  // The program for each GatherVplSource, compiled on first use.
  std::array<std::optional<gl::Program>, 2> programs_;
  gl::Buffer vplRanges_;
  std::vector<gpu::GpuVplRange> uploadedRanges_;  // what vplRanges_ holds
};

}  // namespace penumbra
