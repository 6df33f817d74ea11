#pragma once
// The levels of the multiresolution gather: level 0 is full resolution; level l has
// ceil(size / 2^l) texels per side; the coarsest level is the first whose larger side is at most
// the coarsest size. Every per-level resource of the passes is laid out by one LevelLayout.

#include <vector>

#include <glm/glm.hpp>

namespace penumbra {

// Number of levels from `size` down to a larger side of at most `coarsestSize`.
int levelCountFor(glm::ivec2 size, int coarsestSize);

class LevelLayout {
 public:
  LevelLayout(glm::ivec2 size, int coarsestSize);

  int levelCount() const { return static_cast<int>(sizes_.size()); }
  int coarsest() const { return levelCount() - 1; }
  int coarsestSize() const { return coarsestSize_; }
  glm::ivec2 size(int level) const { return sizes_[static_cast<std::size_t>(level)]; }
  // Where a level's entries start in buffers with an entry per texel of every level.
  unsigned texelOffset(int level) const { return offsets_[static_cast<std::size_t>(level)]; }
  // Texels of all levels together: the size of such buffers.
  unsigned totalTexels() const { return totalTexels_; }

 private:
  int coarsestSize_;
  std::vector<glm::ivec2> sizes_;
  std::vector<unsigned> offsets_;
  unsigned totalTexels_ = 0;
};

}  // namespace penumbra
