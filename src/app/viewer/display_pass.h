#pragma once
// Draws one DisplayView over the current viewport with display.vert/.frag.

#include "app/viewer/display_views.h"
#include "gl/handles.h"
#include "gl/program.h"

namespace penumbra::app {

// Entries of the colour-map table: enough that its linear interpolation matches the map.
inline constexpr int kColourMapTableSize = 256;

class DisplayPass {
 public:
  // Compiles the display program; throws gl::ShaderError.
  DisplayPass();

  // Draws into the bound framebuffer, whose viewport is `viewportSize`.
  void draw(const DisplayView& view, float exposure, glm::ivec2 viewportSize) const;

 private:
  gl::Program program_;
  gl::VertexArray noVertices_;
  gl::Texture colourMapTable_{GL_TEXTURE_1D};
  gl::Sampler nearest_;
};

}  // namespace penumbra::app
