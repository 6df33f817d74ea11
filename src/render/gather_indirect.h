#pragma once
// Indirect light, pass 3: the gather of the secondary VPLs. Indirect light is smooth, so it is
// gathered at one coarser level of the pyramid (its own size setting), then brought to full
// resolution by a bilinear upsampling weighted by agreement of position and normal; a pixel
// whose agreeing coarse texels carry too little weight (edges, thin features) is gathered
// exactly. In naive mode every pixel gathers every secondary VPL at full resolution.

#include "gl/handles.h"
#include "gl/program.h"
#include "render/gbuffer.h"
#include "render/pyramid.h"
#include "render/vpls.h"

namespace penumbra {

class IndirectGatherPass {
 public:
  IndirectGatherPass();
  // `pyramid` null: gather at full resolution; otherwise at `level` of it. Adds the indirect
  // light to `radiance` and writes it alone to `indirect` (both RGBA32F of the G-buffer's size;
  // indirect's w is 1 where a pixel was gathered exactly).
  void run(const GBuffer& gbuffer, const Pyramid* pyramid, int level, const VplBuffer& vpls,
           float planeTolerance, const gl::Texture& radiance, const gl::Texture& indirect);

 private:
  gl::Program gather_;
  gl::Program combine_;
  glm::ivec2 irradianceSize_{0};
  gl::Texture irradiance_{GL_TEXTURE_2D};
};

}  // namespace penumbra
