#include "render/levels.h"

#include <algorithm>

#include "shared.h"

namespace penumbra {

int levelCountFor(glm::ivec2 size, int coarsestSize) {
  int levels = 1;
  while (std::max(size.x, size.y) > coarsestSize && levels < gpu::kMaxLevels) {
    size = (size + 1) / 2;
    ++levels;
  }
  return levels;
}

LevelLayout::LevelLayout(glm::ivec2 size, int coarsestSize) : coarsestSize_(coarsestSize) {
  const int levels = levelCountFor(size, coarsestSize);
  for (int level = 0; level < levels; ++level) {
    sizes_.push_back(size);
    offsets_.push_back(totalTexels_);
    totalTexels_ += static_cast<unsigned>(size.x * size.y);
    size = (size + 1) / 2;
  }
}

}  // namespace penumbra
