#pragma once
// Draws one debug view over the current viewport with display.vert/.frag, coloured by the one
// colouring of the views (render/debug_view_colouring.h).

#include "gl/handles.h"
#include "gl/program.h"
#include "render/debug_view_colouring.h"
#include "render/debug_view_registry.h"

namespace penumbra::app {

class DisplayPass {
 public:
  // Compiles the display program; throws gl::ShaderError.
  DisplayPass();

  // Draws into the bound framebuffer, whose viewport is `viewportSize`.
  void draw(const DebugViewSource& view, float exposure, glm::ivec2 viewportSize) const;

 private:
  gl::Program program_;
  gl::VertexArray noVertices_;
  DebugViewColouring colouring_;
};

}  // namespace penumbra::app
