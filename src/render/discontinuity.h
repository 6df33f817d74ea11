#pragma once
// Pass 2: the discontinuity pyramid. Level 0 holds, per pixel, the relative depth gradient,
// the normal curvature, whether the pixel is a lit surface and its light proximity; every coarser
// level holds the maximum over its footprint, and the G-buffer averaged over the footprint's
// surface pixels.

#include <vector>

#include "gl/handles.h"
#include "gl/program.h"
#include "render/gbuffer.h"
#include "render/levels.h"
#include "render/scene_gpu.h"

namespace penumbra {

// What the discontinuity pass writes: per level, the G-buffer averaged over each texel's
// footprint (the G-buffer itself at level 0) and the discontinuity metrics.
class ReducedGBuffer {
 public:
  ReducedGBuffer(const GBuffer& gbuffer, const LevelLayout& layout);

  const LevelLayout& layout() const { return layout_; }
  const gl::Texture& positionDepth(int level) const;
  const gl::Texture& normal(int level) const;  // w: pixel kind at level 0, surface coverage above
  const gl::Texture& specular(int level) const;
  const gl::Texture& shadowLift(int level) const;  // averaged like the position
  const gl::Texture& faceNormal(int level) const;  // averaged like the normal
  // x: relative depth gradient, y: normal curvature, z: > 0 where the footprint holds pixels
  // other than surfaces.
  const gl::Texture& discontinuity(int level) const { return at(level).discontinuity; }

  // The targets of the discontinuity pass: the averages exist above level 0 only.
  struct Averages {
    gl::Texture& positionDepth;
    gl::Texture& normal;
    gl::Texture& specular;
    gl::Texture& shadowLift;
    gl::Texture& faceNormal;
  };
  Averages averages(int level);
  gl::Texture& discontinuity(int level) { return at(level).discontinuity; }

 private:
  struct Level {
    gl::Texture positionDepth{GL_TEXTURE_2D};
    gl::Texture normal{GL_TEXTURE_2D};
    gl::Texture specular{GL_TEXTURE_2D};
    gl::Texture shadowLift{GL_TEXTURE_2D};
    gl::Texture faceNormal{GL_TEXTURE_2D};
    gl::Texture discontinuity{GL_TEXTURE_2D};
  };
  const Level& at(int level) const { return levels_[static_cast<std::size_t>(level)]; }
  Level& at(int level) { return levels_[static_cast<std::size_t>(level)]; }

  const GBuffer& gbuffer_;
  LevelLayout layout_;
  std::vector<Level> levels_;
};

class DiscontinuityPass {
 public:
  struct Inputs {
    const GBuffer& gbuffer;
    const SceneGpu& scene;  // its lights, for the light proximity
    // Whether the levels average the shadow rays' ends (lift and face normal), which only the
    // visibility passes read: a frame without shadows leaves them as they were.
    bool shadowRayEnds = true;
  };
  struct Outputs {
    ReducedGBuffer& reduced;
  };

  DiscontinuityPass();
  void run(const Inputs& in, const Outputs& out) const;

 private:
  // The pass's programs, with the shadow rays' ends or without them (a constant in each:
  // shaders/pyramid_footprint.glsl says why).
  struct Programs {
    gl::Program firstTwoLevels;  // level 0 per pixel and level 1 from it, one 4x4 block a thread
    gl::Program coarserLevels;   // each level from 2 on from the one below
  };
  static Programs compilePrograms(bool shadowRayEnds);

  Programs withShadowRayEnds_;
  Programs withoutShadowRayEnds_;
};

}  // namespace penumbra
