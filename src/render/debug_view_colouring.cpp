#include "render/debug_view_colouring.h"

#include <array>
#include <span>

#include "gl/dispatch.h"
#include "gl/uniforms.h"
#include "render/readback.h"

namespace penumbra {

DebugViewColouring::DebugViewColouring() : program_(gl::Program::compute("debug_view.comp")) {
  std::array<glm::vec4, kColourMapTableSize> table;
  for (int i = 0; i < kColourMapTableSize; ++i) {
    const float t = static_cast<float>(i) / static_cast<float>(kColourMapTableSize - 1);
    table[static_cast<std::size_t>(i)] = glm::vec4(colourMap(t), 1.0f);
  }
  glTextureStorage1D(colourMapTable_.id(), 1, GL_RGBA32F, kColourMapTableSize);
  glTextureSubImage1D(colourMapTable_.id(), 0, 0, kColourMapTableSize, GL_RGBA, GL_FLOAT,
                      table.data());
  glTextureParameteri(colourMapTable_.id(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTextureParameteri(colourMapTable_.id(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTextureParameteri(colourMapTable_.id(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glSamplerParameteri(nearest_.id(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glSamplerParameteri(nearest_.id(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
}

void DebugViewColouring::prepare(const gl::Program& program, const DebugViewSource& view,
                                 float exposureScale) const {
  // The source goes to the unit of its sampler type; the other unit is left empty, and the
  // shader does not sample it.
  glBindTextureUnit(0, view.unsignedTexture ? 0 : view.texture);
  glBindTextureUnit(1, view.unsignedTexture ? view.texture : 0);
  glBindSampler(0, nearest_.id());
  glBindSampler(1, nearest_.id());
  glBindTextureUnit(2, colourMapTable_.id());

  gl::setUniform(program, "displayKind", view.kind);
  gl::setUniform(program, "sourceIsUnsigned", view.unsignedTexture);
  gl::setUniform(program, "exposureScale", exposureScale);
  gl::setUniform(program, "channel", view.channel);
  gl::setUniform(program, "scalarRange", view.range);
  gl::setUniform(program, "maskChannel", view.maskChannel);
  gl::setUniform(program, "maskValue", view.maskValue);
  std::array<glm::vec3, gpu::kDisplayPaletteSize> palette{};
  for (std::size_t i = 0; i < view.palette.size() && i < palette.size(); ++i)
    palette[i] = view.palette[i].colour;
  gl::setUniform(program, "palette", std::span<const glm::vec3>(palette));
}

void DebugViewColouring::release() const {
  glBindSampler(0, 0);
  glBindSampler(1, 0);
}

Image DebugViewColouring::colour(const DebugViewSource& view) const {
  gl::Texture coloured(GL_TEXTURE_2D);
  glTextureStorage2D(coloured.id(), 1, GL_RGBA32F, view.size.x, view.size.y);
  prepare(program_, view, 1.0f);
  glBindImageTexture(0, coloured.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
  gl::dispatchThreads(program_, view.size);
  glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT);
  glBindImageTexture(0, 0, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
  release();
  return readTexture(coloured.id(), view.size, RowOrder::TopFirst);
}

}  // namespace penumbra
