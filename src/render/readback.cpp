#include "render/readback.h"

#include <algorithm>

namespace penumbra {
namespace {

template <class Texel>
std::vector<Texel> readRows(GLuint texture, GLenum format, GLenum type, glm::ivec2 size,
                            RowOrder order) {
  std::vector<Texel> texels(static_cast<std::size_t>(size.x) * size.y);
  glGetTextureImage(texture, 0, format, type, static_cast<GLsizei>(texels.size() * sizeof(Texel)),
                    texels.data());
  if (order == RowOrder::BottomFirst)
    return texels;
  std::vector<Texel> rows(texels.size());
  for (int y = 0; y < size.y; ++y) {
    std::copy_n(texels.begin() + static_cast<std::ptrdiff_t>(size.y - 1 - y) * size.x, size.x,
                rows.begin() + static_cast<std::ptrdiff_t>(y) * size.x);
  }
  return rows;
}

}  // namespace

Image readTexture(GLuint texture, glm::ivec2 size, RowOrder order) {
  Image image;
  image.width = size.x;
  image.height = size.y;
  image.pixels = readRows<glm::vec4>(texture, GL_RGBA, GL_FLOAT, size, order);
  return image;
}

std::vector<std::uint32_t> readUintTexture(GLuint texture, glm::ivec2 size, RowOrder order) {
  return readRows<std::uint32_t>(texture, GL_RED_INTEGER, GL_UNSIGNED_INT, size, order);
}

}  // namespace penumbra
