#pragma once
// The textures and buffers of the multiresolution gather, one set per level. Level 0 is full
// resolution and uses the G-buffer itself; level l has ceil(size / 2^l) texels per side; the
// coarsest level is the first whose larger side is at most the coarsest size.

#include <vector>

#include "gl/handles.h"
#include "render/gbuffer.h"

namespace penumbra {

// Number of levels from `size` down to a larger side of at most `coarsestSize`.
int levelCountFor(glm::ivec2 size, int coarsestSize);

class Pyramid {
 public:
  Pyramid(const GBuffer& gbuffer, int coarsestSize);

  int levelCount() const { return static_cast<int>(levels_.size()); }
  int coarsestSize() const { return coarsestSize_; }
  glm::ivec2 size(int level) const { return levels_[static_cast<std::size_t>(level)].size; }

  // The G-buffer averaged over each texel's footprint (the G-buffer itself at level 0).
  GLuint positionDepth(int level) const;
  GLuint normal(int level) const;  // w: pixel kind at level 0, surface coverage above
  GLuint specular(int level) const;
  GLuint discontinuity(int level) const { return at(level).discontinuity.id(); }
  GLuint state(int level) const { return at(level).state.id(); }
  GLuint diffuseResult(int level) const { return at(level).diffuseResult.id(); }
  GLuint specularResult(int level) const { return at(level).specularResult.id(); }
  // kVisibilityHasMask / kVisibilityChanges per texel; cleared when shadows are off.
  GLuint visibilityFlags(int level) const { return at(level).visibilityFlags.id(); }
  // Texels of all levels together: the size of buffers with an entry per texel of every level.
  unsigned totalTexels() const { return totalTexels_; }

  // Every level's work list, one after the other, and one DispatchIndirect per level.
  GLuint workList() const { return workList_.id(); }
  GLuint dispatches() const { return dispatches_.id(); }
  unsigned workListOffset(int level) const { return at(level).workListOffset; }

 private:
  struct Level {
    glm::ivec2 size{0};
    unsigned workListOffset = 0;
    gl::Texture positionDepth{GL_TEXTURE_2D};
    gl::Texture normal{GL_TEXTURE_2D};
    gl::Texture specular{GL_TEXTURE_2D};
    gl::Texture discontinuity{GL_TEXTURE_2D};
    gl::Texture state{GL_TEXTURE_2D};
    gl::Texture diffuseResult{GL_TEXTURE_2D};
    gl::Texture specularResult{GL_TEXTURE_2D};
    gl::Texture visibilityFlags{GL_TEXTURE_2D};
  };
  const Level& at(int level) const { return levels_[static_cast<std::size_t>(level)]; }

  const GBuffer& gbuffer_;
  int coarsestSize_;
  std::vector<Level> levels_;
  unsigned totalTexels_ = 0;
  gl::Buffer workList_;
  gl::Buffer dispatches_;
};

}  // namespace penumbra
