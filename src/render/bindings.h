#pragma once
// Image and texture bindings that say what a pass does with each texture. Writing takes a non-const
// texture, so a pass writes only what its outputs hand it; a pass binds everything it uses in its
// own run.

#include <array>
#include <functional>
#include <initializer_list>

#include "gl/handles.h"

namespace penumbra {

// Sampled inputs at texture units 0, 1, ... in order.
inline void bindSampledTextures(
    std::initializer_list<std::reference_wrapper<const gl::Texture>> textures) {
  std::array<GLuint, 16> ids{};
  std::size_t unit = 0;
  for (const gl::Texture& texture : textures)
    ids.at(unit++) = texture.id();
  glBindTextures(0, static_cast<GLsizei>(unit), ids.data());
}

inline void bindImageForReading(GLuint unit, const gl::Texture& texture, GLenum format) {
  glBindImageTexture(unit, texture.id(), 0, GL_FALSE, 0, GL_READ_ONLY, format);
}
inline void bindImageForWriting(GLuint unit, gl::Texture& texture, GLenum format) {
  glBindImageTexture(unit, texture.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, format);
}
inline void bindImageForUpdating(GLuint unit, gl::Texture& texture, GLenum format) {
  glBindImageTexture(unit, texture.id(), 0, GL_FALSE, 0, GL_READ_WRITE, format);
}

}  // namespace penumbra
