#include "render/pyramid.h"

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

Pyramid::Pyramid(const GBuffer& gbuffer, int coarsestSize)
    : gbuffer_(gbuffer),
      coarsestSize_(coarsestSize),
      levels_(static_cast<std::size_t>(levelCountFor(gbuffer.size, coarsestSize))) {
  glm::ivec2 size = gbuffer.size;
  unsigned offset = 0;
  for (std::size_t l = 0; l < levels_.size(); ++l) {
    Level& level = levels_[l];
    level.size = size;
    level.workListOffset = offset;
    offset += static_cast<unsigned>(size.x * size.y);
    if (l > 0) {
      for (const gl::Texture* texture : {&level.positionDepth, &level.normal, &level.specular})
        glTextureStorage2D(texture->id(), 1, GL_RGBA32F, size.x, size.y);
    }
    for (const gl::Texture* texture :
         {&level.discontinuity, &level.diffuseResult, &level.specularResult})
      glTextureStorage2D(texture->id(), 1, GL_RGBA32F, size.x, size.y);
    glTextureStorage2D(level.state.id(), 1, GL_R32UI, size.x, size.y);
    glTextureStorage2D(level.visibilityFlags.id(), 1, GL_R32UI, size.x, size.y);
    size = (size + 1) / 2;
  }
  totalTexels_ = offset;
  glNamedBufferData(workList_.id(), static_cast<GLsizeiptr>(offset) * sizeof(std::uint32_t),
                    nullptr, GL_DYNAMIC_DRAW);
  glNamedBufferData(dispatches_.id(),
                    static_cast<GLsizeiptr>(levels_.size() * sizeof(gpu::DispatchIndirect)),
                    nullptr, GL_DYNAMIC_DRAW);
}

GLuint Pyramid::positionDepth(int level) const {
  return level == 0 ? gbuffer_.positionDepth.id() : at(level).positionDepth.id();
}
GLuint Pyramid::normal(int level) const {
  return level == 0 ? gbuffer_.normalKind.id() : at(level).normal.id();
}
GLuint Pyramid::specular(int level) const {
  return level == 0 ? gbuffer_.specular.id() : at(level).specular.id();
}

}  // namespace penumbra
