#include "app/viewer/display_pass.h"

#include <array>
#include <cmath>

#include "gl/uniforms.h"
#include "render/debug_views.h"

namespace penumbra::app {

DisplayPass::DisplayPass() : program_(gl::Program::graphics("display.vert", "display.frag")) {
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

void DisplayPass::draw(const DisplayView& view, float exposure, glm::ivec2 viewportSize) const {
  // The source goes to the unit of its sampler type; the other unit is left empty, and the
  // shader does not sample it.
  glBindTextureUnit(0, view.unsignedTexture ? 0 : view.texture);
  glBindTextureUnit(1, view.unsignedTexture ? view.texture : 0);
  glBindSampler(0, nearest_.id());
  glBindSampler(1, nearest_.id());
  glBindTextureUnit(2, colourMapTable_.id());

  gl::setUniform(program_, "displayKind", view.kind);
  gl::setUniform(program_, "sourceIsUnsigned", view.unsignedTexture);
  gl::setUniform(program_, "viewportSize", viewportSize);
  gl::setUniform(program_, "exposureScale", std::exp2(exposure));
  gl::setUniform(program_, "channel", view.channel);
  glProgramUniform2f(program_.id(), program_.uniform("scalarRange"), view.range.x, view.range.y);
  gl::setUniform(program_, "maskChannel", view.maskChannel);
  gl::setUniform(program_, "maskValue", view.maskValue);
  std::array<glm::vec3, gpu::kDisplayPaletteSize> palette{};
  for (std::size_t i = 0; i < view.palette.size() && i < palette.size(); ++i)
    palette[i] = view.palette[i].colour;
  glProgramUniform3fv(program_.id(), program_.uniform("palette"), gpu::kDisplayPaletteSize,
                      &palette[0].x);

  glViewport(0, 0, viewportSize.x, viewportSize.y);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  program_.use();
  glBindVertexArray(noVertices_.id());
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glBindVertexArray(0);
  glBindSampler(0, 0);
  glBindSampler(1, 0);
}

}  // namespace penumbra::app
