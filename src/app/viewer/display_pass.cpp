#include "app/viewer/display_pass.h"

#include <cmath>

#include "gl/uniforms.h"

namespace penumbra::app {

DisplayPass::DisplayPass() : program_(gl::Program::graphics("display.vert", "display.frag")) {}

void DisplayPass::draw(const DebugViewSource& view, float exposure, glm::ivec2 viewportSize) const {
  colouring_.prepare(program_, view, std::exp2(exposure));
  gl::setUniform(program_, "viewportSize", viewportSize);

  glViewport(0, 0, viewportSize.x, viewportSize.y);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  program_.use();
  glBindVertexArray(noVertices_.id());
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glBindVertexArray(0);
  colouring_.release();
}

}  // namespace penumbra::app
