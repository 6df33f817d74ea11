#pragma once
// The one way to read textures and buffers back from the GPU. For a texture every caller says
// which row order it wants:
// a picture (row 0 at the top, as image files and Image store it) or GL's texel order (row 0 is
// texel row 0, the bottom of the picture), for data addressed by texel coordinates.

#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "gl/handles.h"
#include "image/image.h"

namespace penumbra {

enum class RowOrder {
  TopFirst,     // row 0 is the top of the picture
  BottomFirst,  // row 0 is GL's texel row 0
};

// Level 0 of an RGBA32F texture of `size` texels.
Image readTexture(GLuint texture, glm::ivec2 size, RowOrder order);
// Level 0 of an R32UI texture of `size` texels, row after row.
std::vector<std::uint32_t> readUintTexture(GLuint texture, glm::ivec2 size, RowOrder order);

// `count` values of a buffer from its `first` value on (a buffer has no rows).
template <class Value>
std::vector<Value> readBuffer(GLuint buffer, std::size_t first, std::size_t count) {
  std::vector<Value> values(count);
  if (count > 0) {
    glGetNamedBufferSubData(buffer, static_cast<GLintptr>(first * sizeof(Value)),
                            static_cast<GLsizeiptr>(count * sizeof(Value)), values.data());
  }
  return values;
}

}  // namespace penumbra
